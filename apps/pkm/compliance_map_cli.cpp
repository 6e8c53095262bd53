// pkm compliance --map --out FILE: the lowest translational stiffness of the strut-only model and its
// direction over a plane grid of poses (src/stiffness/stiffness_map.hpp, docs/dynamic_compliance.md), as a
// CSV, with a summary on stdout or as JSON.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "compliance_cli.hpp"
#include "formats/stiffness_csv.hpp"
#include "io/pose_input.hpp"
#include "progress_display.hpp"
#include "stiffness/stiffness_map.hpp"

namespace pkm::cli {
namespace {

int compliance_map_error(const std::string& prefix, const Error& error) {
  Error e = error;
  if (!prefix.empty()) e.message = prefix + ": " + e.message;
  return report_error("compliance", e);
}

}  // namespace

int run_compliance_map(const ComplianceMapArguments& arguments) {
  auto machine = load_machine_or_report(arguments.machine_path);
  if (!machine) return compliance_map_error("", machine.error());
  const Mechanism& mech = *machine->mechanism;
  // The springs first: a machine without strut stiffness is refused before any grid is looked at.
  auto parameters = stiffness::strut_stiffness_of(*machine);
  if (!parameters) return compliance_map_error("", parameters.error());
  auto grid = map_grid_poses(mech, arguments.grid);
  if (!grid) return compliance_map_error("", grid.error());
  ProgressDisplay progress("compliance", "stiffness over the grid");
  auto points = stiffness::stiffness_map(grid->poses, stiffness::strut_compliance_at(*machine, *parameters));
  progress.finish();
  if (!points) return compliance_map_error("", points.error());
  if (Status written = formats::write_stiffness_map_csv(arguments.out_path, mech, grid->poses, *points);
      !written) {
    return compliance_map_error("--out", written.error());
  }
  const auto s = stiffness::summarise_stiffness_map(*points);
  const double share = s.points > 0 ? static_cast<double>(s.with_value) / s.points : 0.0;
  const auto pose_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return user_from_pose(mech, grid->poses[index]);
  };
  const auto value_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return (*points)[index].lowest_stiffness_N_um;
  };
  const auto direction_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    const Eigen::Vector3d& d = (*points)[index].direction;
    return {d.x(), d.y(), d.z()};
  };
  if (arguments.json) {
    print_json({{"machine", machine->source},
                {"out", arguments.out_path},
                {"model", "strut-only"},
                {"plane", to_string(grid->grid.plane)},
                {"centre", user_from_pose(mech, grid->grid.centre)},
                {"range_mm", grid->grid.half_range_mm},
                {"step_mm", grid->grid.step_mm},
                {"points_per_axis", static_cast<int>(grid->points_per_axis)},
                {"points", s.points},
                {"with_stiffness", s.with_value},
                {"reachable_share", share},
                {"unreachable", s.unreachable},
                {"out_of_range", s.out_of_range},
                {"singular", s.singular},
                {"min_stiffness_N_um", value_at(s.lowest_index)},
                {"min_direction", direction_at(s.lowest_index)},
                {"min_pose", pose_at(s.lowest_index)},
                {"max_stiffness_N_um", value_at(s.highest_index)},
                {"max_pose", pose_at(s.highest_index)}});
    return 0;
  }
  std::cout << fmt::format(
      "{} ({}): lowest translational stiffness (struts as the springs) over the {} plane through {}, ±{:g} "
      "mm "
      "by {:g} mm\n",
      machine->name, machine->source, to_string(grid->grid.plane), map_pose_text(mech, grid->grid.centre),
      grid->grid.half_range_mm, grid->grid.step_mm);
  std::cout << fmt::format(
      "  {} points ({:.0f} × {:.0f}): {} with a value ({:.1f} %), {} unreachable, {} beyond the actuators' "
      "range, {} singular\n",
      s.points, grid->points_per_axis, grid->points_per_axis, s.with_value, 100.0 * share, s.unreachable,
      s.out_of_range, s.singular);
  if (s.lowest_index >= 0) {
    const Eigen::Vector3d& d = (*points)[s.lowest_index].direction;
    std::cout << fmt::format("  weakest  {:10.3f} N/µm along [{:+.4f} {:+.4f} {:+.4f}] at {}\n",
                             (*points)[s.lowest_index].lowest_stiffness_N_um, d.x(), d.y(), d.z(),
                             map_pose_text(mech, grid->poses[s.lowest_index]));
    std::cout << fmt::format("  stiffest {:10.3f} N/µm at {}\n",
                             (*points)[s.highest_index].lowest_stiffness_N_um,
                             map_pose_text(mech, grid->poses[s.highest_index]));
  } else {
    std::cout << "  no point of the grid has a value\n";
  }
  std::cout << fmt::format("  map: {}\n", arguments.out_path);
  return 0;
}

}  // namespace pkm::cli
