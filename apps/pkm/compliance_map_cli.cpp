// pkm compliance --map --out FILE: the lowest translational stiffness of the strut-only model and its
// direction over a plane grid of poses (pipeline/compliance_map_job.hpp, docs/dynamic_compliance.md), as a
// CSV, with a summary on stdout or as JSON.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "compliance_cli.hpp"
#include "io/pose_input.hpp"
#include "pipeline/compliance_map_job.hpp"
#include "progress_display.hpp"

namespace pkm::cli {
namespace {

void print_compliance_map_json(const Machine& machine, const dynamics::PlaneGrid& grid,
                               const pipeline::ComplianceMapJobResult& r, const std::string& out_path) {
  const stiffness::StiffnessMapSummary& s = r.summary;
  const auto value_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return r.points[index].lowest_stiffness_N_um;
  };
  const auto direction_at = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    const Eigen::Vector3d& d = r.points[index].direction;
    return {d.x(), d.y(), d.z()};
  };
  nlohmann::json json = map_summary_json(machine, grid, static_cast<int>(r.points_per_axis), r.poses, s,
                                         "with_stiffness", out_path);
  json["model"] = "strut-only";
  json["min_stiffness_N_um"] = value_at(s.lowest_index);
  json["min_direction"] = direction_at(s.lowest_index);
  json["max_stiffness_N_um"] = value_at(s.highest_index);
  print_json(json);
}

void print_compliance_map(const Machine& machine, const dynamics::PlaneGrid& grid,
                          const pipeline::ComplianceMapJobResult& r, const std::string& out_path) {
  const Mechanism& mech = *machine.mechanism;
  const stiffness::StiffnessMapSummary& s = r.summary;
  const double share = s.points > 0 ? static_cast<double>(s.with_value) / s.points : 0.0;
  std::cout << fmt::format(
      "{} ({}): lowest translational stiffness (struts as the springs) over the {} plane through {}, ±{:g} "
      "mm "
      "by {:g} mm\n",
      machine.name, machine.source, to_string(grid.plane), map_pose_text(mech, grid.centre),
      grid.half_range_mm, grid.step_mm);
  std::cout << fmt::format(
      "  {} points ({:.0f} × {:.0f}): {} with a value ({:.1f} %), {} unreachable, {} beyond the actuators' "
      "range, {} singular\n",
      s.points, r.points_per_axis, r.points_per_axis, s.with_value, 100.0 * share, s.unreachable,
      s.out_of_range, s.singular);
  if (s.lowest_index >= 0) {
    const Eigen::Vector3d& d = r.points[s.lowest_index].direction;
    std::cout << fmt::format("  weakest  {:10.3f} N/µm along [{:+.4f} {:+.4f} {:+.4f}] at {}\n",
                             r.points[s.lowest_index].lowest_stiffness_N_um, d.x(), d.y(), d.z(),
                             map_pose_text(mech, r.poses[s.lowest_index]));
    std::cout << fmt::format("  stiffest {:10.3f} N/µm at {}\n",
                             r.points[s.highest_index].lowest_stiffness_N_um,
                             map_pose_text(mech, r.poses[s.highest_index]));
  } else {
    std::cout << "  no point of the grid has a value\n";
  }
  std::cout << fmt::format("  map: {}\n", out_path);
}

}  // namespace

int run_compliance_map(const ComplianceMapArguments& arguments) {
  auto machine = load_machine_or_report(arguments.machine_path);
  if (!machine) return report_error("compliance", machine.error());
  auto grid = map_plane_grid(*machine->mechanism, arguments.grid);
  if (!grid) return report_error("compliance", grid.error());
  ProgressDisplay progress("compliance", "stiffness over the grid");
  auto map =
      pipeline::run_compliance_map_job(*machine, {*grid, arguments.out_path, "--out", progress.sink()});
  progress.finish();
  if (!map) return report_error("compliance", map.error());
  if (arguments.json)
    print_compliance_map_json(*machine, *grid, *map, arguments.out_path);
  else
    print_compliance_map(*machine, *grid, *map, arguments.out_path);
  return 0;
}

}  // namespace pkm::cli
