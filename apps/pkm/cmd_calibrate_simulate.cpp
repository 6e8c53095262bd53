// pkm calibrate simulate --machine M.yaml --out DIR [--trials N] [--joint-error-mm E] [--offset-error-mm E]
//   [plan and instrument options as `calibrate plan`] [--write-measurements FILE [--noise-free]] [--json]:
// Monte-Carlo trials of perturb → measure with noise → identify → judge at held-out poses (DIR/trials.csv,
// DIR/summary.json), and one simulated measurement file with its true parameters
// (pipeline/calibration_run.hpp, docs/calibration.md).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "cmd_calibrate.hpp"
#include "number_options.hpp"
#include "pipeline/calibration_checks.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

void add_calibrate_simulate_command(CLI::App& calibrate, int& exit_code) {
  auto* cmd = calibrate.add_subcommand(
      "simulate",
      "Monte-Carlo trials: perturbed machines measured with noise, identified, judged at held-out poses");
  auto job = std::make_shared<pipeline::CalibrationSimulateJob>();
  auto machine_path = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>("d-optimal");
  auto text = std::make_shared<CalibrateInstrumentText>();
  auto noise_free = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML): the drawing the trials perturb")
      ->required();
  cmd->add_option("--out", job->out_directory, "directory for trials.csv and summary.json")->required();
  add_calibrate_plan_options(*cmd, job->plan, *method);
  add_calibrate_instrument_options(*cmd, job->instrument, *text);
  cmd->add_option("--trials", job->trials, "Monte-Carlo trials")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationTrials)));
  cmd->add_option("--joint-error-mm", job->joint_error_mm,
                  "the true joints: uniform ± this around the drawing, mm")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationJointErrorMm)));
  cmd->add_option("--offset-error-mm", job->offset_error_mm, "the true drive offsets: uniform ± this, mm")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationOffsetErrorMm)));
  cmd->add_option(
      "--write-measurements", job->measurements_path,
      "also write one simulated measurement file here (a machine drawn from --seed), its fixture beside "
      "it and DIR/true_parameters.csv");
  cmd->add_flag(
      "--noise-free", *noise_free,
      "the file of --write-measurements without noise (--sigma-mm still weighs it); the trials keep theirs");
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    job->noise = !*noise_free;
    auto spec = calibrate_plan_spec(job->plan, *method, cmd->count("--poses") > 0);
    if (!spec) {
      exit_code = report_error("calibrate simulate", spec.error());
      return;
    }
    job->plan = *spec;
    auto instrument = calibrate_instrument(job->instrument, *text);
    if (!instrument) {
      exit_code = report_error("calibrate simulate", instrument.error());
      return;
    }
    job->instrument = *instrument;
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("calibrate simulate", machine.error());
      return;
    }
    ProgressDisplay progress("calibrate simulate", "Monte-Carlo trials");
    auto result = pipeline::calibration_simulate(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("calibrate simulate", result.error());
      return;
    }
    if (*json) {
      print_json(result->summary);
      return;
    }
    const calibration::MonteCarloSummary& mc = result->monte_carlo;
    std::cout << fmt::format(
        "{} trials on {} ({}): {} plan of {} poses, {} parameters, joints ±{} mm, offsets ±{} mm, "
        "σ {} mm\n",
        mc.trials, machine->name, *machine_path, pipeline::to_string(job->plan.method), result->plan_poses,
        result->parameters, job->joint_error_mm, job->offset_error_mm, job->instrument.sigma_mm);
    std::cout << fmt::format(
        "  held-out tool error   rms median {:.4g} mm (p90 {:.4g}), max median {:.4g} mm (p90 {:.4g})\n",
        mc.held_out_rms_mm.median, mc.held_out_rms_mm.p90, mc.held_out_max_mm.median, mc.held_out_max_mm.p90);
    std::cout << fmt::format(
        "  parameter error       max median {:.4g} mm (p90 {:.4g}), rms median {:.4g} mm\n",
        mc.parameter_error_max_mm.median, mc.parameter_error_max_mm.p90, mc.parameter_error_rms_mm.median);
    std::cout << fmt::format("  failed / not converged {} / {}; mean condition {:.4g}\n", mc.failed,
                             mc.not_converged, mc.mean_condition_number);
    for (const auto& warning : result->summary["warnings"])
      std::cerr << "warning: " << warning.get<std::string>() << "\n";
    std::cout << fmt::format("  written               {}/trials.csv, summary.json{}\n", job->out_directory,
                             job->measurements_path.empty()
                                 ? std::string()
                                 : fmt::format(", true_parameters.csv; {}", job->measurements_path));
  });
}

}  // namespace pkm::cli
