// `pkm calibrate identify` (calibration_run.hpp): the measurement file read against the machine, the poses
// kept aside, the identification, and its outputs written as one set: the calibrated machine file (checked by
// loading it back), parameters.csv, residuals.csv, summary.json and the optional report.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "calibration/residuals.hpp"
#include "io/atomic_file.hpp"
#include "io/calibration_file.hpp"
#include "io/input_file.hpp"
#include "io/json_text.hpp"
#include "io/machine_file.hpp"
#include "io/measurement_file.hpp"
#include "io/output_set.hpp"
#include "pipeline/calibration_checks.hpp"
#include "pipeline/calibration_identify_outputs.hpp"
#include "pipeline/calibration_run.hpp"
#include "pipeline/calibration_setup.hpp"
#include "pipeline/run_report.hpp"

namespace pkm::pipeline {
namespace {

using calibration::MeasurementSet;

// The poses kept aside: `count` spread evenly over the file, so that they sample the whole plan.
std::vector<bool> calid_held_out_mask(int poses, int count) {
  std::vector<bool> held(static_cast<std::size_t>(poses), false);
  for (int k = 0; k < count; ++k) held[static_cast<std::size_t>((2 * k + 1) * poses / (2 * count))] = true;
  return held;
}

// Too few equations for the parameters is a fault of the file: named at its last pose.
Status calid_enough_equations(const MeasurementSet& data, int rows, int parameters, int holdout) {
  if (rows >= parameters) return ok_status();
  const calibration::MeasuredPose& last = data.poses.back();
  const double per_pose = static_cast<double>(rows) / static_cast<double>(data.poses.size());
  const int more = static_cast<int>(std::ceil((parameters - rows) / per_pose));
  return Error{
      ErrorCode::bad_input,
      fmt::format(
          "{}:{}:1: pose_id: {} equations from {} pose{}{} for {} parameters: measure at least {} more "
          "poses",
          data.source, last.line, rows, data.poses.size(), data.poses.size() == 1 ? "" : "s",
          holdout > 0 ? fmt::format(" (after {} held out)", holdout) : std::string(), parameters, more),
      ErrorLocation{data.source, last.line, 1, "pose_id"}};
}

// The calibrated machine file must load and give the identified model's inverse kinematics: a check that the
// file every other command will read says what was identified.
Status calid_check_calibrated(const std::string& text, const std::string& path, const Mechanism& identified,
                              const MeasurementSet& data) {
  auto loaded = parse_machine_text(text, path);
  if (!loaded) return loaded.error();
  double worst = 0.0;
  for (const calibration::MeasuredPose& pose : data.poses) {
    auto solved = identified.forward(pose.readings, identified.home());
    if (!solved) continue;
    auto mine = identified.inverse(solved->pose);
    auto theirs = loaded->mechanism->inverse(solved->pose);
    if (!mine || !theirs)
      return make_error(ErrorCode::not_converged,
                        fmt::format("{}: a measured pose is out of reach of the calibrated file", path));
    worst = std::max(worst, (*mine - *theirs).cwiseAbs().maxCoeff());
  }
  if (worst > 1e-9) {
    return make_error(
        ErrorCode::not_converged,
        fmt::format("{}: the calibrated file's actuators differ from the identified model's by {:.3g}", path,
                    worst));
  }
  return ok_status();
}

}  // namespace

Result<CalibrationIdentifyResult> calibration_identify(const Machine& machine,
                                                       const CalibrationIdentifyJob& job) {
  if (Status valid = check_calibration_identify_job(job); !valid) return valid.error();
  auto model = calibration_model(machine);
  if (!model) return model.error();
  auto layout = calibration::parameter_layout(**model);
  if (!layout) return layout.error();
  if (job.holdout < 0) return make_error(ErrorCode::bad_input, fmt::format("{} held-out poses", job.holdout));
  MeasurementReadOptions read = measurement_options_for(machine, job.holdout + 1);
  read.fixture_path = job.fixture_path;
  auto all = read_measurement_file(job.measurements_path, read);
  if (!all) return all.error();

  MeasurementSet identification = *all, held_out = *all;
  identification.poses.clear();
  held_out.poses.clear();
  const std::vector<bool> held = calid_held_out_mask(static_cast<int>(all->poses.size()), job.holdout);
  for (std::size_t p = 0; p < all->poses.size(); ++p)
    (held[p] ? held_out : identification).poses.push_back(all->poses[p]);

  auto residuals = calibration::ResidualModel::make(**model, identification);
  if (!residuals) return residuals.error();
  if (Status enough = calid_enough_equations(identification, residuals->rows(), layout->size(), job.holdout);
      !enough)
    return enough.error();
  auto identified = calibration::identify(**model, identification);
  if (!identified) return identified.error();
  if (identified->status == calibration::IdentificationStatus::not_converged) {
    return make_error(ErrorCode::not_converged,
                      fmt::format("{}: the identification did not converge ({}); nothing written",
                                  job.measurements_path, identified->solver_message));
  }
  if (job.strict && identified->status != calibration::IdentificationStatus::identified) {
    return make_error(
        ErrorCode::singular,
        fmt::format("{}: the measurements identify {} of {} parameter directions (strict); nothing written",
                    job.measurements_path, identified->at_start.rank, identified->at_start.parameters));
  }

  CalibrationIdentifyResult result;
  auto held_errors = calibration_held_out_errors(**model, *identified->mechanism, held_out);
  if (!held_errors) return held_errors.error();
  result.held_out = *held_errors;
  auto residual_rows = calibration_residual_rows(*residuals, **model, *identified->mechanism);
  if (!residual_rows) return residual_rows.error();

  auto poses_csv = calibration_poses_csv(**model, *identified->mechanism, *all, held);
  if (!poses_csv) return poses_csv.error();

  auto original = read_text_input(machine.source, "machine file");
  if (!original) return original.error();
  const std::string note = fmt::format(
      "identified from {} ({} poses, {} held out): rms residual {:.4g} -> {:.4g} mm, rank {} of {}, {}",
      job.measurements_path, identification.poses.size(), held_out.poses.size(), identified->before.rms_mm,
      identified->after.rms_mm, identified->at_start.rank, identified->at_start.parameters,
      calibration::to_string(identified->status));
  const std::string calibrated = calibrated_machine_text(*original, identified->groups, note);
  if (Status checked = calid_check_calibrated(calibrated, job.calibrated_path, *identified->mechanism, *all);
      !checked)
    return checked.error();

  OutputSet outputs{"calibrate identify"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  auto staged = outputs.stage_file(job.calibrated_path);
  if (!staged) return staged.error();
  if (Status written = write_file_atomically(*staged, calibrated); !written) return written.error();
  if (Status written = write_file_atomically(outputs.staged_path("parameters.csv"),
                                             calibration_parameters_csv(*identified));
      !written)
    return written.error();
  if (Status written = write_file_atomically(outputs.staged_path("residuals.csv"), *residual_rows); !written)
    return written.error();
  if (Status written = write_file_atomically(outputs.staged_path("poses.csv"), *poses_csv); !written)
    return written.error();
  result.summary = calibration_identify_summary(machine, job, *all, *identified, result.held_out,
                                                static_cast<int>(identification.poses.size()));
  if (Status written =
          write_file_atomically(outputs.staged_path("summary.json"), json_text(result.summary) + "\n");
      !written)
    return written.error();
  if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.identification = std::move(*identified);
  return result;
}

}  // namespace pkm::pipeline
