// pkm calibrate identify --machine M.yaml --measurements F.csv --out calibrated.yaml [--dir DIR] [--fixture
// F]
//   [--holdout N] [--strict] [--report FILE.html] [--json]: the machine's geometry and drive offsets
//   identified
// from a measurement file; writes the calibrated machine file (every other command reads it) and DIR/
// parameters.csv, residuals.csv, summary.json (pipeline/calibration_run.hpp, docs/calibration.md).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "cmd_calibrate.hpp"
#include "number_options.hpp"
#include "pipeline/calibration_checks.hpp"
#include "progress_display.hpp"

namespace pkm::cli {
namespace {

// DIR when --dir is not given: beside the calibrated file, named after it.
std::string calid_default_directory(const std::string& calibrated_path) {
  const std::filesystem::path file(calibrated_path);
  return (file.parent_path() / (file.stem().string() + "_identify")).string();
}

void calid_print(const pipeline::CalibrationIdentifyJob& job,
                 const pipeline::CalibrationIdentifyResult& result, const Machine& machine) {
  const calibration::IdentificationResult& r = result.identification;
  std::cout << fmt::format("{}: {} on {} ({}), {} iterations ({})\n", job.measurements_path,
                           calibration::to_string(r.status), machine.name, machine.source, r.iterations,
                           r.solver_message);
  print_calibrate_identifiability(r.at_start);
  std::cout << fmt::format(
      "  residuals      rms {:.4g} → {:.4g} mm, max {:.4g} → {:.4g} mm (variance factor {:.3g})\n",
      r.before.rms_mm, r.after.rms_mm, r.before.max_mm, r.after.max_mm, r.variance_factor);
  if (result.held_out.poses > 0) {
    const pipeline::HeldOutErrors& h = result.held_out;
    std::cout << fmt::format("  held out       {} poses: rms {:.4g} → {:.4g} mm, max {:.4g} → {:.4g} mm\n",
                             h.poses, h.rms_before_mm, h.rms_after_mm, h.max_before_mm, h.max_after_mm);
  }
  for (const auto& warning : result.summary["warnings"])
    std::cerr << "warning: " << warning.get<std::string>() << "\n";
  std::cout << fmt::format("  written        {}; {}/parameters.csv, residuals.csv, summary.json{}\n",
                           job.calibrated_path, job.out_directory,
                           job.report_path.empty() ? std::string() : fmt::format("; {}", job.report_path));
}

}  // namespace

void add_calibrate_identify_command(CLI::App& calibrate, int& exit_code) {
  auto* cmd = calibrate.add_subcommand("identify", "the geometry and drive offsets from a measurement file");
  auto job = std::make_shared<pipeline::CalibrationIdentifyJob>();
  auto machine_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path,
                  "machine file (YAML): the drawing, the start of the identification")
      ->required();
  cmd->add_option("--measurements", job->measurements_path,
                  "measurement file (CSV: tracker or ballbar, docs/calibration.md)")
      ->required();
  cmd->add_option("--out", job->calibrated_path, "the calibrated machine file to write (YAML)")->required();
  cmd->add_option("--dir", job->out_directory,
                  "directory for parameters.csv, residuals.csv and summary.json (default: beside --out, "
                  "NAME_identify)");
  cmd->add_option("--fixture", job->fixture_path,
                  "fixture file, instead of the one the measurement file names");
  cmd->add_option("--holdout", job->holdout, "poses kept aside (spread over the file) to judge the result")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationHoldout)));
  cmd->add_flag("--strict", job->strict, "a partial identification is an error (exit 4), nothing written");
  cmd->add_option("--report", job->report_path, "also write the HTML report of the run to this file");
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    if (job->out_directory.empty()) job->out_directory = calid_default_directory(job->calibrated_path);
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("calibrate identify", machine.error());
      return;
    }
    ProgressDisplay progress("calibrate identify", "identifying the geometry");
    auto result = pipeline::calibration_identify(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("calibrate identify", result.error());
      return;
    }
    if (*json) {
      print_json(result->summary);
      return;
    }
    calid_print(*job, *result, *machine);
  });
}

}  // namespace pkm::cli
