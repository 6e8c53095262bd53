#pragma once
// The outputs of `pkm calibrate identify` (calibration_run.hpp, docs/calibration.md): the held-out errors,
// the residuals before and after per measured quantity, the parameter table and the summary.
#include <nlohmann/json.hpp>
#include <string>

#include "calibration/identify.hpp"
#include "calibration/residuals.hpp"
#include "machine/machine.hpp"
#include "pipeline/calibration_run.hpp"

namespace pkm::pipeline {

/// How far each held-out measurement is from what the model predicts from the pose's drive readings (a
/// target's position, mm; a ballbar's length), for the drawing and for the identified model.
Result<HeldOutErrors> calibration_held_out_errors(const Mechanism& nominal, const Mechanism& identified,
                                                  const calibration::MeasurementSet& held_out);

/// residuals.csv: one row per residual of the identification (pose_id, line, form, quantity, before and after
/// in mm and weighted).
Result<std::string> calibration_residual_rows(const calibration::ResidualModel& residuals,
                                              const Mechanism& nominal, const Mechanism& identified);

/// poses.csv: every measured pose (held-out ones too) as the identified model solves its readings, with the
/// tool point the drawing would put there and the distance between the two (what the calibration corrects).
Result<std::string> calibration_poses_csv(const Mechanism& nominal, const Mechanism& identified,
                                          const calibration::MeasurementSet& all,
                                          const std::vector<bool>& held_out);

/// parameters.csv: name, unit, nominal, identified, change, sigma, identifiable.
std::string calibration_parameters_csv(const calibration::IdentificationResult& result);

/// summary.json of the run.
nlohmann::json calibration_identify_summary(const Machine& machine, const CalibrationIdentifyJob& job,
                                            const calibration::MeasurementSet& all,
                                            const calibration::IdentificationResult& result,
                                            const HeldOutErrors& held_out, int identification_poses);

}  // namespace pkm::pipeline
