#include "map_grid.hpp"

#include <fmt/format.h>

#include "io/pose_input.hpp"
#include "number_options.hpp"

namespace pkm::cli {
namespace {

Error map_grid_error(const std::string& flag, const Error& error) {
  Error e = error;
  e.message = flag + ": " + e.message;
  return e;
}

}  // namespace

nlohmann::json map_summary_json(const Machine& machine, const dynamics::PlaneGrid& grid, int points_per_axis,
                                const std::vector<Pose>& poses, const dynamics::MapPointCounts& counts,
                                const std::string& with_value_key, const std::string& out_path) {
  const Mechanism& mech = *machine.mechanism;
  const auto pose_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return user_from_pose(mech, poses[index]);
  };
  const double share = counts.points > 0 ? static_cast<double>(counts.with_value) / counts.points : 0.0;
  return {{"machine", machine.source},
          {"out", out_path},
          {"plane", to_string(grid.plane)},
          {"centre", user_from_pose(mech, grid.centre)},
          {"range_mm", grid.half_range_mm},
          {"step_mm", grid.step_mm},
          {"points_per_axis", points_per_axis},
          {"points", counts.points},
          {with_value_key, counts.with_value},
          {"reachable_share", share},
          {"unreachable", counts.unreachable},
          {"out_of_range", counts.out_of_range},
          {"singular", counts.singular},
          {"min_pose", pose_at(counts.lowest_index)},
          {"max_pose", pose_at(counts.highest_index)}};
}

void add_map_grid_options(CLI::App& command, MapGridArguments& arguments, CLI::Option* map_flag) {
  // Kept as text: map_plane_grid reads it against the mechanism, as --pose is read.
  command
      .add_option("--centre,--center", arguments.centre_text,
                  "with --map: the grid's centre pose, as --pose (default: the machine's home)")
      ->needs(map_flag);
  // Like pkm check's sample: beyond 10 m no machine pkm models moves.
  command
      .add_option("--range-mm", arguments.half_range_mm,
                  "with --map: the grid covers the centre ± this along both axes, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, true, true, "mm"}))
      ->needs(map_flag);
  command.add_option("--step-mm", arguments.step_mm, "with --map: the grid's step, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, false, true, "mm"}))
      ->needs(map_flag);
  command.add_option("--plane", arguments.plane, "with --map: the grid's plane through the centre, xy|xz|yz")
      ->capture_default_str()
      ->check(CLI::IsMember({"xy", "xz", "yz"}))
      ->needs(map_flag);
}

Result<dynamics::PlaneGrid> map_plane_grid(const Mechanism& mechanism, const MapGridArguments& arguments) {
  dynamics::PlaneGrid grid;
  grid.centre = mechanism.home();
  if (!arguments.centre_text.empty()) {
    auto values = parse_number_list(arguments.centre_text, "--centre");
    if (!values) return values.error();
    auto centre = pose_from_user(mechanism, *values, "--centre");
    if (!centre) return centre.error();
    grid.centre = *centre;
  }
  auto plane = dynamics::grid_plane_from_string(arguments.plane);
  if (!plane) return map_grid_error("--plane", plane.error());
  if (mechanism.is_planar() && *plane != dynamics::GridPlane::xy) {
    return map_grid_error("--plane " + arguments.plane,
                          make_error(ErrorCode::bad_input, "a planar machine moves in the xy plane only"));
  }
  grid.plane = *plane;
  grid.half_range_mm = arguments.half_range_mm;
  grid.step_mm = arguments.step_mm;
  const double side = dynamics::grid_points_per_axis(grid.half_range_mm, grid.step_mm);
  if (side * side > kMaxMapGridPoints) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("--step-mm {:g} with --range-mm {:g} gives {:.0f} × {:.0f} = {:.3g} grid "
                    "points, more than {:.0f}; take a larger --step-mm or a smaller --range-mm",
                    grid.step_mm, grid.half_range_mm, side, side, side * side, kMaxMapGridPoints));
  }
  return grid;
}

std::string map_pose_text(const Mechanism& mechanism, const Pose& pose) {
  return fmt::format("{:g}", fmt::join(user_from_pose(mechanism, pose), ", "));
}

}  // namespace pkm::cli
