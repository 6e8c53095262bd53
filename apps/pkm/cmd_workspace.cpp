// pkm workspace --machine M.yaml [--plane xy|xz|yz|U,V] [--centre P] [--range-mm R] [--step-mm S]
//   [--range-deg R] [--step-deg S] [--grid3d] [--stiffness] [--frequencies] [--calibration-plan DIR]
//   [--threads N] --out DIR [--report FILE.html] [--json]:
// the workspace map (src/workspace/, docs/workspace.md): per cell of a section or a 3-D grid whether the
// machine can stand there or which limit stops it, sign of det J, condition number, δρ and S_x, S_y, S_z
// (Smirnov 2019, eq. 144–146), and on request the lowest stiffness, the lowest natural frequency and the tool
// error predicted after measuring a calibration plan (pipeline/calibration_workspace.hpp). Writes
// DIR/workspace.csv and DIR/summary.json as one output set, with the HTML report as one more member
// (pipeline/workspace_job.hpp); prints the summary.
#include <fmt/format.h>

#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "cmd_workspace_grid.hpp"
#include "commands.hpp"
#include "formats/workspace_output.hpp"
#include "number_options.hpp"
#include "pipeline/workspace_job.hpp"
#include "progress_display.hpp"

namespace pkm::cli {
namespace {

struct WorkspaceArguments {
  std::string machine_path, out_dir, report_path;
  std::string calibration_plan;  ///< the directory of `pkm calibrate plan` ("": no such layer)
  WorkspaceGridArguments grid;
  workspace::WorkspaceMapOptions options;
  bool json = false;
};

// "calibration plan DIR: 12 d-optimal poses, σ 0.01 mm; rank 42 of 42, condition 5.6e+03".
std::string workspace_calibration_text(const pipeline::CalibrationWorkspaceLayer& layer) {
  const calibration::Identifiability& id = layer.prediction->identifiability();
  return fmt::format("calibration plan {}: {} {}{}poses, σ {} mm; rank {} of {}, condition {:.3g}",
                     layer.plan.directory, layer.plan.poses.size(), layer.plan.method,
                     layer.plan.method.empty() ? "" : " ", layer.plan.instrument.sigma_mm, id.rank,
                     id.parameters, id.identifiable_condition_number);
}

void print_workspace_summary(const Machine& machine, const workspace::WorkspaceMap& map,
                             const workspace::WorkspaceMapSummary& s, const WorkspaceArguments& a,
                             const std::optional<pipeline::CalibrationWorkspaceLayer>& calibration_layer) {
  using workspace::CellStatus;
  const Mechanism& mech = *machine.mechanism;
  const auto count = [&](CellStatus status) { return s.status_cells[static_cast<std::size_t>(status)]; };
  std::cout << fmt::format("{} ({}): workspace over {}\n", machine.name, machine.source,
                           describe_workspace_grid(mech, map.grid));
  const long ok = count(CellStatus::ok);
  std::cout << fmt::format(
      "  {} cells ({}): {} ok ({:.1f} %), {} unreachable, {} beyond the actuators' range, {} beyond a "
      "joint's "
      "swing, {} singular, {} beyond the condition number limit\n",
      s.cells, fmt::join(map.points_per_axis, " × "), ok, s.cells > 0 ? 100.0 * ok / s.cells : 0.0,
      count(CellStatus::unreachable), count(CellStatus::actuator_range), count(CellStatus::joint_angle),
      count(CellStatus::singular), count(CellStatus::conditioning));
  std::string stopping;
  for (int j = 0; j < mech.actuator_count(); ++j) {
    const long n = s.actuator_range_cells[static_cast<std::size_t>(j)];
    if (n > 0) fmt::format_to(std::back_inserter(stopping), " q{} {}", j + 1, n);
  }
  if (!stopping.empty()) std::cout << fmt::format("  stopped by actuator:{}\n", stopping);
  if (calibration_layer) std::cout << "  " << workspace_calibration_text(*calibration_layer) << "\n";
  if (ok > 0) {
    std::cout << fmt::format("  det J over the ok cells: {} positive, {} negative\n", s.determinant_positive,
                             s.determinant_negative);
  }
  const workspace::GridCells cells(map.grid, mech.convention());
  for (const workspace::LayerInfo& info : workspace::workspace_layers()) {
    const workspace::LayerExtremes& e = s.layers[static_cast<std::size_t>(info.layer)];
    if (e.cells == 0) continue;
    std::cout << fmt::format("  {:<34} {:>10.4g} … {:<10.4g} {:<5} min at {}, max at {}\n", info.label, e.min,
                             e.max, info.unit, map_pose_text(mech, cells.pose(e.min_cell)),
                             map_pose_text(mech, cells.pose(e.max_cell)));
  }
  std::cout << fmt::format("  written {}/{}, {}{}\n", a.out_dir, formats::kWorkspaceCsv,
                           formats::kWorkspaceSummaryJson,
                           a.report_path.empty() ? "" : fmt::format(", report {}", a.report_path));
}

void print_workspace_json(const pipeline::WorkspaceJobResult& r, const WorkspaceArguments& a) {
  nlohmann::json j = r.summary_json;
  j["out"] = a.out_dir;
  if (!a.report_path.empty()) j["report"] = a.report_path;
  if (r.calibration) {
    const calibration::Identifiability& id = r.calibration->prediction->identifiability();
    j["calibration_plan"] = {{"directory", r.calibration->plan.directory},
                             {"poses", r.calibration->plan.poses.size()},
                             {"sigma_mm", r.calibration->plan.instrument.sigma_mm},
                             {"rank", id.rank},
                             {"parameters", id.parameters}};
  }
  print_json(j);
}

int run_workspace(const WorkspaceArguments& a) {
  auto machine = load_machine_or_report(a.machine_path);
  if (!machine) return report_error("workspace", machine.error());
  auto grid = workspace_grid_from(*machine->mechanism, a.grid);
  if (!grid) return report_error("workspace", grid.error());
  ProgressDisplay progress("workspace", "mapping the grid");
  pipeline::WorkspaceJob job{*grid,
                             a.options,
                             a.calibration_plan,
                             a.out_dir,
                             a.report_path,
                             progress.sink(),
                             [](std::string_view warning) { std::cerr << "warning: " << warning << "\n"; }};
  auto result = pipeline::run_workspace_job(*machine, job);
  progress.finish();
  if (!result) return report_error("workspace", result.error());
  if (a.json) {
    print_workspace_json(*result, a);
    return 0;
  }
  print_workspace_summary(*machine, result->map, result->summary, a, result->calibration);
  return 0;
}

}  // namespace

void add_workspace_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "workspace",
      "workspace map over a section or a 3-D grid: reachable or which limit stops it, det J sign, condition "
      "number, error amplification δρ and S_x, S_y, S_z (Smirnov 2019, eq. 144–146), optional stiffness, "
      "natural frequency and predicted error after calibration");
  auto a = std::make_shared<WorkspaceArguments>();
  MapGridArguments& section = a->grid.section;
  cmd->add_option("--machine", a->machine_path, "machine file (YAML)")->required();
  cmd->add_option("--out", a->out_dir, "directory for workspace.csv and summary.json")->required();
  // Kept as text: read against the mechanism, as --pose is read.
  cmd->add_option("--centre,--center", section.centre_text,
                  "the grid's centre pose, as --pose (default: the machine's home)");
  auto* plane = cmd->add_option("--plane", section.plane,
                                "the section through the centre: xy|xz|yz, or two coordinates such as x,B")
                    ->capture_default_str();
  // Like pkm modes --map: beyond 10 m no machine pkm models moves.
  cmd->add_option("--range-mm", section.half_range_mm, "the grid covers the centre ± this along x, y, z, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, true, true, "mm"}));
  cmd->add_option("--step-mm", section.step_mm, "the grid's step along x, y, z, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, false, true, "mm"}));
  cmd->add_option("--range-deg", a->grid.half_range_deg,
                  "the grid covers the centre ± this along an angle, deg")
      ->capture_default_str()
      ->check(number_in({0.0, 180.0, true, true, "deg"}));
  cmd->add_option("--step-deg", a->grid.step_deg, "the grid's step along an angle, deg")
      ->capture_default_str()
      ->check(number_in({0.0, 180.0, false, true, "deg"}));
  cmd->add_flag("--grid3d", a->grid.grid3d,
                "a 3-D grid of positions (x, y, z about the centre) instead of a section")
      ->excludes(plane);
  cmd->add_flag("--stiffness", a->options.stiffness,
                "also the lowest translational stiffness, N/µm (stiffness: or the dynamics: springs)");
  cmd->add_flag("--frequencies", a->options.frequencies,
                "also the lowest natural frequency, Hz (dynamics: with strut stiffness)");
  cmd->add_option("--calibration-plan", a->calibration_plan,
                  "also the tool error predicted after measuring this plan, mm: the directory `pkm calibrate "
                  "plan --out` wrote (plan.csv, summary.json)");
  cmd->add_option("--threads", a->options.threads, "worker threads (0: every core)")
      ->capture_default_str()
      ->check(number_in({0.0, 1024.0, true, true, "", true}));
  cmd->add_option("--report", a->report_path, "also write the HTML report with a heat map per layer");
  cmd->add_flag("--json", a->json, "print the summary as JSON");
  cmd->callback([a, &exit_code] { exit_code = run_workspace(*a); });
}

}  // namespace pkm::cli
