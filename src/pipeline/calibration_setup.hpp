#pragma once
// What the three `pkm calibrate` runs share (calibration_run.hpp): the model whose parameters are identified
// (the machine's mechanism with drive offsets), the instrument as a measurement setup, the machine's limits
// as a plan filter, the plan and the held-out poses a spec asks for, and the JSON and CSV pieces of their
// outputs.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calibration/identifiability.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/plan_prediction.hpp"
#include "calibration/synthetic_measurements.hpp"
#include "machine/machine.hpp"
#include "pipeline/calibration_run.hpp"

namespace pkm::pipeline {

/// The machine's mechanism with its drive offsets as parameters (zero when the file has none).
Result<std::unique_ptr<Mechanism>> calibration_model(const Machine& machine);

/// The instrument as the library's setup; reads the fixture file when one is named.
Result<calibration::MeasurementSetup> calibration_setup(const CalibrationInstrument& instrument);

/// The machine's limits (actuator travel, passive-joint swings, conditioning) as a plan filter.
calibration::PoseFilter calibration_limits_filter(const Machine& machine);

/// The poses `spec` asks for on `model`, within the machine's limits.
Result<calibration::PosePlan> calibration_pose_plan(const Machine& machine, const Mechanism& model,
                                                    const CalibrationPlanSpec& spec,
                                                    const calibration::MeasurementSetup& setup);

/// `spec.held_out` random poses in the spec's box within the limits, drawn apart from the plan's.
Result<std::vector<Pose>> calibration_held_out(const Machine& machine, const Mechanism& model,
                                               const CalibrationPlanSpec& spec);

/// What `pkm calibrate plan` and `simulate` both start from: the model, the instrument, the planned and the
/// held-out poses, and the plan's predicted identifiability and tool error.
struct CalibrationPrepared {
  std::unique_ptr<Mechanism> model;
  calibration::MeasurementSetup setup;
  calibration::PosePlan plan;
  std::vector<Pose> held_out;
  calibration::PlanPrediction prediction;
};
Result<CalibrationPrepared> calibration_prepare(const Machine& machine, const CalibrationPlanSpec& spec,
                                                const CalibrationInstrument& instrument);

/// "P01", "P02", … (as many digits as `count` needs).
std::string calibration_pose_id(int index, int count);

/// The pose columns of a CSV row for `mechanism`: "x_mm,y_mm,z_mm,a1_deg,a2_deg,a3_deg" (angles in the
/// machine's convention, as `pkm ik --pose` takes them), fewer for planar mechanisms.
std::string calibration_pose_header(const Mechanism& mechanism);
std::string calibration_pose_fields(const Mechanism& mechanism, const Pose& pose);
/// ",L1,…,Ln" and the readings in the file's units (mm, or deg).
std::string calibration_reading_header(int count);
std::string calibration_reading_fields(const Mechanism& mechanism, const ActuatorVector& readings);

/// The instrument as summary.json states it.
nlohmann::json calibration_instrument_json(const CalibrationInstrument& instrument,
                                           const calibration::MeasurementSetup& setup);
/// Rank, conditioning and the named combinations of an identifiability analysis.
nlohmann::json calibration_identifiability_json(const calibration::Identifiability& identifiability);

}  // namespace pkm::pipeline
