// pkm calibrate plan --machine M.yaml --out DIR [--method seven-pose|random|d-optimal] [--poses N]
//   [--fixture F | --ballbar-centre X,Y,Z] [--sigma-mm S] [--box-mm B --box-deg A] [--held-out K] [--seed S]
//   [--strict] [--json]: the poses to measure within the machine's limits and the accuracy they predict
// (DIR/plan.csv, DIR/summary.json; pipeline/calibration_run.hpp, docs/calibration.md).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_calibrate.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

void add_calibrate_plan_command(CLI::App& calibrate, int& exit_code) {
  auto* cmd = calibrate.add_subcommand(
      "plan", "the poses to measure, within the limits, with their predicted accuracy");
  auto job = std::make_shared<pipeline::CalibrationPlanJob>();
  auto machine_path = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>("d-optimal");
  auto text = std::make_shared<CalibrateInstrumentText>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--out", job->out_directory, "directory for plan.csv and summary.json")->required();
  add_calibrate_plan_options(*cmd, job->plan, *method);
  add_calibrate_instrument_options(*cmd, job->instrument, *text);
  cmd->add_flag("--strict", job->strict, "a plan that cannot identify every parameter is an error (exit 4)");
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    auto spec = calibrate_plan_spec(job->plan, *method, cmd->count("--poses") > 0);
    if (!spec) {
      exit_code = report_error("calibrate plan", spec.error());
      return;
    }
    job->plan = *spec;
    auto instrument = calibrate_instrument(job->instrument, *text);
    if (!instrument) {
      exit_code = report_error("calibrate plan", instrument.error());
      return;
    }
    job->instrument = *instrument;
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("calibrate plan", machine.error());
      return;
    }
    ProgressDisplay progress("calibrate plan", "choosing the poses");
    auto result = pipeline::calibration_plan(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("calibrate plan", result.error());
      return;
    }
    if (*json) {
      print_json(result->summary);
      return;
    }
    const calibration::PlanPrediction& p = result->prediction;
    std::cout << fmt::format("{} plan: {} poses on {} ({}), measured with σ {} mm\n",
                             pipeline::to_string(job->plan.method), result->plan.poses.size(), machine->name,
                             *machine_path, job->instrument.sigma_mm);
    print_calibrate_identifiability(p.identifiability);
    std::cout << fmt::format(
        "  predicted tool error  rms {:.4g} mm, p90 {:.4g} mm, max {:.4g} mm at {} held-out poses "
        "(measurement noise only)\n",
        p.tool_rms_mm, p.tool_p90_mm, p.tool_max_mm, p.tool_sd_mm.size());
    for (const auto& warning : result->summary["warnings"])
      std::cerr << "warning: " << warning.get<std::string>() << "\n";
    std::cout << fmt::format("  written        {}/plan.csv, summary.json\n", job->out_directory);
  });
}

}  // namespace pkm::cli
