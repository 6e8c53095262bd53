#include "modes_map.hpp"

#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "io/pose_input.hpp"
#include "pipeline/modes_map_job.hpp"

namespace pkm::cli {
namespace {

void print_modes_map_json(const Machine& machine, const dynamics::PlaneGrid& grid,
                          const pipeline::ModesMapJobResult& r, const std::string& out_path) {
  const dynamics::FrequencyMapSummary& s = r.summary;
  const auto frequency = [&](int index) -> nlohmann::json {
    if (index < 0) return nullptr;
    return r.points[index].lowest_frequency_Hz;
  };
  nlohmann::json json = map_summary_json(machine, grid, static_cast<int>(r.points_per_axis), r.poses, s,
                                         "with_frequency", out_path);
  json["min_frequency_Hz"] = frequency(s.lowest_index);
  json["max_frequency_Hz"] = frequency(s.highest_index);
  print_json(json);
}

void print_modes_map(const Machine& machine, const dynamics::PlaneGrid& grid,
                     const pipeline::ModesMapJobResult& r, const std::string& out_path) {
  const Mechanism& mech = *machine.mechanism;
  const dynamics::FrequencyMapSummary& s = r.summary;
  const double share = s.points > 0 ? static_cast<double>(s.with_value) / s.points : 0.0;
  const double side = r.points_per_axis;
  std::cout << fmt::format(
      "{} ({}): lowest natural frequency over the {} plane through {}, ±{:g} mm by {:g} mm\n", machine.name,
      machine.source, to_string(grid.plane), map_pose_text(mech, grid.centre), grid.half_range_mm,
      grid.step_mm);
  std::cout << fmt::format(
      "  {} points ({:.0f} × {:.0f}): {} with a frequency ({:.1f} %), {} unreachable, {} beyond the "
      "actuators' "
      "range, {} singular or unstable\n",
      s.points, side, side, s.with_value, 100.0 * share, s.unreachable, s.out_of_range, s.singular);
  if (s.lowest_index >= 0) {
    std::cout << fmt::format("  lowest   {:10.3f} Hz at {}\n", r.points[s.lowest_index].lowest_frequency_Hz,
                             map_pose_text(mech, r.poses[s.lowest_index]));
    std::cout << fmt::format("  highest  {:10.3f} Hz at {}\n", r.points[s.highest_index].lowest_frequency_Hz,
                             map_pose_text(mech, r.poses[s.highest_index]));
  } else {
    std::cout << "  no point of the grid has a frequency\n";
  }
  std::cout << fmt::format("  map: {}\n", out_path);
}

}  // namespace

int run_modes_map(const ModesMapArguments& arguments) {
  auto machine = load_machine_or_report(arguments.machine_path);
  if (!machine) return report_error("modes", machine.error());
  auto grid = map_plane_grid(*machine->mechanism, arguments.grid);
  if (!grid) return report_error("modes", grid.error());
  auto map = pipeline::run_modes_map_job(*machine, {*grid, arguments.out_path, "--out"});
  if (!map) return report_error("modes", map.error());
  if (arguments.json)
    print_modes_map_json(*machine, *grid, *map, arguments.out_path);
  else
    print_modes_map(*machine, *grid, *map, arguments.out_path);
  return 0;
}

}  // namespace pkm::cli
