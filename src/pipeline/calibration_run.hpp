#pragma once
// `pkm calibrate plan | simulate | identify` as library calls (docs/calibration.md): a typed job
// in, an output set written (replacing a previous run's only when all of it succeeded), a typed result out.
// The identified parameters are the mechanism's geometry groups plus the drive offsets (src/calibration/,
// machine/actuator_offsets.hpp).
//  - plan: the poses to measure, within the machine's limits, and the accuracy they predict for a measurement
//    sigma (plan.csv, summary.json).
//  - simulate: Monte-Carlo trials of perturb → measure with noise → identify → judge at held-out poses
//    (trials.csv, summary.json), and optionally one simulated measurement file with its true parameters.
//  - identify: the parameters from a measurement file; the calibrated machine file (the drawing plus a
//    `calibration:` section, io/calibration_file.hpp) and parameters.csv, residuals.csv, summary.json and
//    an optional HTML report.
// A plan or a measurement set that cannot identify every parameter is reported as such (rank, the dropped
// combinations by name), never as converged; `strict` makes it an error.
#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "calibration/identify.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/plan_prediction.hpp"
#include "calibration/simulate.hpp"
#include "machine/machine.hpp"

namespace pkm::pipeline {

/// What is measured at every pose.
struct CalibrationInstrument {
  std::string fixture_path;        ///< the tracker's targets (io/fixture_file.hpp); "": the triangular plate
  double plate_radius_mm = 100.0;  ///< of the default plate (the dissertation's)
  std::optional<Eigen::Vector3d> ballbar_centre_mm;  ///< a ballbar to this ball instead of a tracker
  double sigma_mm = 0.01;                            ///< of every measured coordinate or length
};

enum class CalibrationPlanMethod { seven_pose, random, d_optimal };
/// "seven-pose", "random", "d-optimal".
std::optional<CalibrationPlanMethod> calibration_plan_method(std::string_view name);
std::string_view to_string(CalibrationPlanMethod method);

/// How the poses to measure are chosen (calibration/plan_design.hpp).
struct CalibrationPlanSpec {
  CalibrationPlanMethod method = CalibrationPlanMethod::d_optimal;
  int poses = 0;                  ///< 0: the seven-pose plan's n + 1 (the other methods need a count)
  double box_mm = 50.0;           ///< random and D-optimal poses: ± on x, y, z around home
  double box_deg = 10.0;          ///< ... and ± on each angle
  double strut_change_mm = 10.0;  ///< seven-pose: each strut's change (mm, or deg for angular actuators)
  int candidates = 400;           ///< D-optimal: random poses to choose from
  int held_out = 50;              ///< random poses in the box where the tool error is predicted or judged
  std::uint64_t seed = 1;         ///< random draws of poses (and of simulated machines and noise)
};

struct CalibrationPlanJob {
  CalibrationPlanSpec plan;
  CalibrationInstrument instrument;
  bool strict = false;  ///< a plan that cannot identify every parameter is an error
  std::string out_directory;
};

struct CalibrationPlanResult {
  calibration::PosePlan plan;
  calibration::PlanPrediction prediction;
  int parameters = 0;
  nlohmann::json summary;  ///< summary.json as written
};

/// The plan and its prediction; DIR/plan.csv and DIR/summary.json.
Result<CalibrationPlanResult> calibration_plan(const Machine& machine, const CalibrationPlanJob& job);

struct CalibrationSimulateJob {
  CalibrationPlanSpec plan;
  CalibrationInstrument instrument;
  int trials = 20;
  double joint_error_mm = 0.1;   ///< the true machine's joints: uniform ± this around the drawing
  double offset_error_mm = 0.1;  ///< its drive offsets
  bool noise = true;             ///< false: measurements without noise (sigma still weighs them)
  std::string out_directory;
  /// Also one simulated measurement file here ("": none): a machine drawn from the seed, measured along the
  /// plan, with its true parameters in DIR/true_parameters.csv (and the fixture next to the file if it is not
  /// a file already).
  std::string measurements_path;
};

struct CalibrationSimulateResult {
  calibration::MonteCarloSummary monte_carlo;
  int parameters = 0;
  int plan_poses = 0;
  nlohmann::json summary;
};

/// Monte-Carlo trials; DIR/trials.csv, DIR/summary.json (and the measurement file).
Result<CalibrationSimulateResult> calibration_simulate(const Machine& machine,
                                                       const CalibrationSimulateJob& job);

struct CalibrationIdentifyJob {
  std::string measurements_path;
  std::string fixture_path;     ///< instead of the file's `# fixture:` ("": the file's)
  int holdout = 0;              ///< poses kept aside (spread over the file) to judge the result
  bool strict = false;          ///< partial identification is an error
  std::string calibrated_path;  ///< the calibrated machine file
  std::string out_directory;    ///< parameters.csv, residuals.csv, summary.json
  std::string report_path;      ///< the HTML report ("": none)
};

/// Residual statistics of the held-out poses, before (drawing) and after (identified).
struct HeldOutErrors {
  int poses = 0;
  int measurements = 0;
  double rms_before_mm = 0.0, max_before_mm = 0.0;
  double rms_after_mm = 0.0, max_after_mm = 0.0;
};

struct CalibrationIdentifyResult {
  calibration::IdentificationResult identification;
  HeldOutErrors held_out;
  nlohmann::json summary;
};

/// The identification and its outputs, written as one set with the calibrated machine file.
Result<CalibrationIdentifyResult> calibration_identify(const Machine& machine,
                                                       const CalibrationIdentifyJob& job);

}  // namespace pkm::pipeline
