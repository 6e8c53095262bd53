#include "modes_map.hpp"

#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "dynamics/frequency_map.hpp"
#include "dynamics/pose_grid.hpp"
#include "io/atomic_file.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {
namespace {

/// The CSV's pose columns: the numbers `pkm modes --pose` takes (x_mm … and the angles in degrees, named
/// in the machine's convention; planar machines their controlled coordinates only).
std::vector<std::string> map_pose_columns(const Mechanism& mech) {
  const auto names = pose_coordinate_names(mech);
  const AxisMask mask = mech.controlled_axes();
  std::vector<std::string> columns;
  for (int i = 0; i < 6; ++i) {
    if (mech.is_planar() && !mask.controlled[i]) continue;  // as user_from_pose
    columns.push_back(names[i] + (i < 3 ? "_mm" : "_deg"));
  }
  return columns;
}

/// One row per grid point; the frequency is empty where the point has none, and `status` says why.
std::string frequency_map_csv(const Mechanism& mech, const std::vector<Pose>& poses,
                              const std::vector<dynamics::FrequencyMapPoint>& points) {
  std::string csv = fmt::format("{},lowest_frequency_Hz,status\n", fmt::join(map_pose_columns(mech), ","));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    for (double v : user_from_pose(mech, poses[i])) csv += fmt::format("{:.6f},", v);
    if (points[i].status == dynamics::MapPointStatus::ok)
      csv += fmt::format("{:.6f}", points[i].lowest_frequency_Hz);
    csv += fmt::format(",{}\n", to_string(points[i].status));
  }
  return csv;
}

std::string map_pose_text(const Mechanism& mech, const Pose& pose) {
  return fmt::format("{:g}", fmt::join(user_from_pose(mech, pose), ", "));
}

int modes_map_error(const std::string& prefix, const Error& error) {
  Error e = error;
  if (!prefix.empty()) e.message = prefix + ": " + e.message;
  return report_error("modes", e);
}

}  // namespace

int run_modes_map(const ModesMapArguments& arguments) {
  auto machine = load_machine_or_report(arguments.machine_path);
  if (!machine) return modes_map_error("", machine.error());
  const Mechanism& mech = *machine->mechanism;
  // The model first: a machine without stiffness is refused before any grid is looked at.
  auto model = dynamics::make_elastic_model(*machine);
  if (!model) return modes_map_error("", model.error());
  dynamics::PlaneGrid grid;
  grid.centre = mech.home();
  if (!arguments.centre_text.empty()) {
    auto values = parse_number_list(arguments.centre_text, "--centre");
    if (!values) return modes_map_error("", values.error());
    auto centre = pose_from_user(mech, *values, "--centre");
    if (!centre) return modes_map_error("", centre.error());
    grid.centre = *centre;
  }
  auto plane = dynamics::grid_plane_from_string(arguments.plane);
  if (!plane) return modes_map_error("--plane", plane.error());
  if (mech.is_planar() && *plane != dynamics::GridPlane::xy) {
    return modes_map_error("--plane " + arguments.plane,
                           make_error(ErrorCode::bad_input, "a planar machine moves in the xy plane only"));
  }
  grid.plane = *plane;
  grid.half_range_mm = arguments.half_range_mm;
  grid.step_mm = arguments.step_mm;
  const double side = dynamics::grid_points_per_axis(grid.half_range_mm, grid.step_mm);
  if (side * side > kMaxModesMapPoints) {
    return modes_map_error(
        "", make_error(
                ErrorCode::bad_input,
                fmt::format("--step-mm {:g} with --range-mm {:g} gives {:.0f} × {:.0f} = {:.3g} grid "
                            "points, more than {:.0f}; take a larger --step-mm or a smaller --range-mm",
                            grid.step_mm, grid.half_range_mm, side, side, side * side, kMaxModesMapPoints)));
  }
  auto poses = dynamics::plane_grid_poses(grid, kMaxModesMapPoints);
  if (!poses) return modes_map_error("", poses.error());
  const auto points = dynamics::frequency_map(*machine, *model, *poses);
  const auto s = dynamics::summarise_frequency_map(points);
  if (Status written = write_file_atomically(arguments.out_path, frequency_map_csv(mech, *poses, points));
      !written) {
    return modes_map_error("--out", written.error());
  }
  const double share = s.points > 0 ? static_cast<double>(s.with_frequency) / s.points : 0.0;
  const auto at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return user_from_pose(mech, (*poses)[index]);
  };
  const auto frequency = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return points[index].lowest_frequency_Hz;
  };
  if (arguments.json) {
    print_json({{"machine", machine->source},
                {"out", arguments.out_path},
                {"plane", to_string(grid.plane)},
                {"centre", user_from_pose(mech, grid.centre)},
                {"range_mm", grid.half_range_mm},
                {"step_mm", grid.step_mm},
                {"points_per_axis", static_cast<int>(side)},
                {"points", s.points},
                {"with_frequency", s.with_frequency},
                {"reachable_share", share},
                {"unreachable", s.unreachable},
                {"out_of_range", s.out_of_range},
                {"singular", s.singular},
                {"min_frequency_Hz", frequency(s.lowest_index)},
                {"min_pose", at(s.lowest_index)},
                {"max_frequency_Hz", frequency(s.highest_index)},
                {"max_pose", at(s.highest_index)}});
    return 0;
  }
  std::cout << fmt::format(
      "{} ({}): lowest natural frequency over the {} plane through {}, ±{:g} mm by {:g} mm\n", machine->name,
      machine->source, to_string(grid.plane), map_pose_text(mech, grid.centre), grid.half_range_mm,
      grid.step_mm);
  std::cout << fmt::format(
      "  {} points ({:.0f} × {:.0f}): {} with a frequency ({:.1f} %), {} unreachable, {} beyond the "
      "actuators' "
      "range, {} singular or unstable\n",
      s.points, side, side, s.with_frequency, 100.0 * share, s.unreachable, s.out_of_range, s.singular);
  if (s.lowest_index >= 0) {
    std::cout << fmt::format("  lowest   {:10.3f} Hz at {}\n", points[s.lowest_index].lowest_frequency_Hz,
                             map_pose_text(mech, (*poses)[s.lowest_index]));
    std::cout << fmt::format("  highest  {:10.3f} Hz at {}\n", points[s.highest_index].lowest_frequency_Hz,
                             map_pose_text(mech, (*poses)[s.highest_index]));
  } else {
    std::cout << "  no point of the grid has a frequency\n";
  }
  std::cout << fmt::format("  map: {}\n", arguments.out_path);
  return 0;
}

}  // namespace pkm::cli
