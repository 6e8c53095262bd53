#include "modes_map.hpp"

#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "dynamics/frequency_map.hpp"
#include "dynamics/pose_grid.hpp"
#include "formats/frequency_map_csv.hpp"
#include "io/output_file.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {
namespace {

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
  const MapGridArguments grid_arguments{arguments.centre_text, arguments.plane, arguments.half_range_mm,
                                        arguments.step_mm};
  auto map_grid = map_grid_poses(mech, grid_arguments);
  if (!map_grid) return modes_map_error("", map_grid.error());
  const dynamics::PlaneGrid& grid = map_grid->grid;
  const double side = map_grid->points_per_axis;
  const std::vector<Pose>* poses = &map_grid->poses;
  const auto points = dynamics::frequency_map(*machine, *model, *poses);
  const auto s = dynamics::summarise_frequency_map(points);
  if (Status written =
          write_output_file(arguments.out_path, formats::frequency_map_csv(mech, *poses, points));
      !written) {
    return modes_map_error("--out", written.error());
  }
  const double share = s.points > 0 ? static_cast<double>(s.with_value) / s.points : 0.0;
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
                {"with_frequency", s.with_value},
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
      s.points, side, side, s.with_value, 100.0 * share, s.unreachable, s.out_of_range, s.singular);
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
