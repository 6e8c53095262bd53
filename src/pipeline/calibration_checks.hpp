#pragma once
// The calibration jobs' parameters checked once, in the library, for every caller (the CLI, Python): each
// message names the parameter and the range it must lie in ("box_mm 20000: expected 0 … 10000 mm").
#include "core/result.hpp"
#include "pipeline/calibration_run.hpp"
#include "pipeline/parameter_range.hpp"

namespace pkm::pipeline {

inline constexpr ParameterRange kCalibrationPoses{"poses", 1, 10000, true, "", true};
inline constexpr ParameterRange kCalibrationBoxMm{"box_mm", 0, 10000, true, "mm"};
inline constexpr ParameterRange kCalibrationBoxDeg{"box_deg", 0, 90, true, "deg"};
inline constexpr ParameterRange kCalibrationStrutChangeMm{"strut_change_mm", -1000, 1000, true, "mm"};
inline constexpr ParameterRange kCalibrationCandidates{"candidates", 1, 100000, true, "", true};
inline constexpr ParameterRange kCalibrationHeldOut{"held_out", 0, 100000, true, "", true};
/// A plate of 1 m radius is larger than any platform pkm models.
inline constexpr ParameterRange kCalibrationPlateRadiusMm{"plate_radius_mm", 0, 1000, false, "mm"};
inline constexpr ParameterRange kCalibrationSigmaMm{"sigma_mm", 0, 10, false, "mm"};
inline constexpr ParameterRange kCalibrationTrials{"trials", 0, 100000, true, "", true};
inline constexpr ParameterRange kCalibrationJointErrorMm{"joint_error_mm", 0, 100, true, "mm"};
inline constexpr ParameterRange kCalibrationOffsetErrorMm{"offset_error_mm", 0, 100, true, "mm"};
inline constexpr ParameterRange kCalibrationHoldout{"holdout", 0, 100000, true, "", true};

/// poses (1 … 10000; 0, the method's own count, for the seven-pose plan only), box_mm, box_deg,
/// strut_change_mm, candidates, held_out.
Status check_calibration_plan_spec(const CalibrationPlanSpec& spec);
/// plate_radius_mm, sigma_mm, and no fixture with a ballbar.
Status check_calibration_instrument(const CalibrationInstrument& instrument);
/// The plan and the instrument, trials, joint_error_mm, offset_error_mm, and noise only off with a
/// measurement file to write.
Status check_calibration_simulate_job(const CalibrationSimulateJob& job);
/// holdout.
Status check_calibration_identify_job(const CalibrationIdentifyJob& job);

}  // namespace pkm::pipeline
