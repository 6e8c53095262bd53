// pkm simulate PLAN_DIR --machine M.yaml [--load LOAD] [--out DIR] [--report FILE] [--no-split] [--json]: a
// planned run on the machine in simulation, the drives' servo loops closed on the elastic machine under the
// process load with the drives' imperfections; the tool's actual path, its contour error and the error's
// parts (src/pipeline/simulate_program.hpp, docs/simulate.md).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/simulate_program.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

void print_simulate_summary(const pipeline::SimulateJob& job, const pipeline::SimulateResult& r) {
  std::cout << fmt::format("{}: {} ticks, {:.3f} s of motion on the elastic machine in its servo loops{}\n",
                           job.plan_directory, r.ticks, r.simulated_s,
                           job.load.empty() ? "" : ", under the process load");
  std::cout << fmt::format("  contour error   max {:.4f} mm (line {}, t = {:.3f} s), rms {:.4f} mm\n",
                           r.total.max_mm, r.total.max_line, r.total.max_time_s, r.total.rms_mm);
  if (job.split) {
    for (const pipeline::ContourPart& p : r.parts)
      std::cout << fmt::format("  {:<8}        max {:.4f} mm (line {}), rms {:.4f} mm\n", p.name, p.max_mm,
                               p.max_line, p.rms_mm);
  }
  if (!r.worst_lines.empty()) {
    std::string lines;
    for (const auto& [line, error] : r.worst_lines) lines += fmt::format(" {} ({:.4f})", line, error);
    std::cout << "  worst lines    " << lines << "\n";
  }
  std::cout << fmt::format("  written         {}/simulate.csv, simulate_summary.json, simulate.svg{}\n",
                           job.out_directory.empty() ? job.plan_directory : job.out_directory,
                           job.report_path.empty() ? std::string() : "; " + job.report_path);
}

}  // namespace

void add_simulate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("simulate",
                                 "a planned run on the machine in simulation: servo loops on the elastic "
                                 "machine under the process load, "
                                 "the tool's actual path and its contour error split into causes");
  auto job = std::make_shared<pipeline::SimulateJob>();
  auto machine_path = std::make_shared<std::string>();
  auto load_text = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto no_split = std::make_shared<bool>(false);
  cmd->add_option("plan", job->plan_directory,
                  "output directory of pkm plan (ticks.h5, or actuators.csv and path.csv)")
      ->required();
  cmd->add_option("--machine", *machine_path,
                  "machine file (YAML) with dynamics: (strut stiffness) and servo: sections")
      ->required();
  cmd->add_option("--load", *load_text,
                  "the process load: key=value pairs (tangential=N,normal=N,axial=N,force=X:Y:Z,...), or "
                  "@FILE (YAML load cases, or CSV per program line)");
  cmd->add_option("--out", job->out_directory,
                  "where to write simulate.csv, simulate_summary.json, simulate.svg (default: the plan "
                  "directory)");
  cmd->add_option("--report", job->report_path,
                  "also write the plan's HTML report with the simulation's charts to this file");
  cmd->add_flag("--no-split", *no_split, "only the full machine: do not split the error into its causes");
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    job->split = !*no_split;
    if (!load_text->empty()) {
      auto load = statics::parse_load_spec(*load_text);
      if (!load) {
        exit_code =
            report_error("simulate", make_error(load.error().code, "--load: " + load.error().message));
        return;
      }
      job->load = std::move(*load);
    }
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("simulate", machine.error());
      return;
    }
    ProgressDisplay progress("simulate", "reading the plan");
    job->progress = progress.sink();
    auto result = pipeline::simulate_program(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("simulate", result.error());
      return;
    }
    if (*json) {
      print_json(result->json);
      return;
    }
    print_simulate_summary(*job, *result);
  });
}

}  // namespace pkm::cli
