#include "pipeline/calibration_checks.hpp"

namespace pkm::pipeline {

Status check_calibration_plan_spec(const CalibrationPlanSpec& spec) {
  // 0: the seven-pose plan's own count, n + 1.
  if (spec.poses != 0 || spec.method != CalibrationPlanMethod::seven_pose) {
    if (Status s = check_in_range(kCalibrationPoses, spec.poses); !s) return s;
  }
  for (const auto& [range, value] :
       {std::pair{kCalibrationBoxMm, spec.box_mm}, std::pair{kCalibrationBoxDeg, spec.box_deg},
        std::pair{kCalibrationStrutChangeMm, spec.strut_change_mm},
        std::pair{kCalibrationCandidates, static_cast<double>(spec.candidates)},
        std::pair{kCalibrationHeldOut, static_cast<double>(spec.held_out)}}) {
    if (Status s = check_in_range(range, value); !s) return s;
  }
  return ok_status();
}

Status check_calibration_instrument(const CalibrationInstrument& instrument) {
  if (Status s = check_in_range(kCalibrationPlateRadiusMm, instrument.plate_radius_mm); !s) return s;
  if (Status s = check_in_range(kCalibrationSigmaMm, instrument.sigma_mm); !s) return s;
  if (instrument.ballbar_centre_mm && !instrument.fixture_path.empty())
    return make_error(ErrorCode::bad_input,
                      "ballbar_centre_mm and fixture_path: a ballbar measures no fixture");
  return ok_status();
}

Status check_calibration_simulate_job(const CalibrationSimulateJob& job) {
  if (Status s = check_calibration_plan_spec(job.plan); !s) return s;
  if (Status s = check_calibration_instrument(job.instrument); !s) return s;
  for (const auto& [range, value] : {std::pair{kCalibrationTrials, static_cast<double>(job.trials)},
                                     std::pair{kCalibrationJointErrorMm, job.joint_error_mm},
                                     std::pair{kCalibrationOffsetErrorMm, job.offset_error_mm}}) {
    if (Status s = check_in_range(range, value); !s) return s;
  }
  if (!job.noise && job.measurements_path.empty())
    return make_error(ErrorCode::bad_input,
                      "noise_free: only with a measurement file to write (write_measurements)");
  return ok_status();
}

Status check_calibration_identify_job(const CalibrationIdentifyJob& job) {
  return check_in_range(kCalibrationHoldout, job.holdout);
}

}  // namespace pkm::pipeline
