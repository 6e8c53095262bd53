#pragma once
// `pkm workspace --calibration-plan DIR` (docs/workspace.md): the workspace map's layer "predicted error
// after calibration" for a plan that `pkm calibrate plan` wrote (calibration_run.hpp). DIR/plan.csv gives the
// planned poses, DIR/summary.json the instrument (a tracker with the plate or a fixture file, or a ballbar,
// and σ). Measuring that plan on the machine's calibration model (its geometry and drive offsets) gives the
// identified parameters' covariance Σ (plan_jacobian.hpp, identifiability.hpp: rank-truncated (JᵀJ)⁺); the
// layer at a pose is sqrt(trace(G·Σ·Gᵀ)) with G the tool point's sensitivity to the parameters there
// (tool_sensitivity.hpp): the same measure, computed the same way, as plan_prediction.hpp gives for its
// held-out poses. It is the error from measurement noise alone; what the plan leaves unidentifiable adds its
// own error, which the prediction does not see.
#include <memory>
#include <string>
#include <vector>

#include "calibration/identifiability.hpp"
#include "calibration/synthetic_measurements.hpp"
#include "calibration/tool_sensitivity.hpp"
#include "machine/machine.hpp"
#include "pipeline/calibration_run.hpp"
#include "workspace/workspace_map.hpp"

namespace pkm::pipeline {

/// A plan of `pkm calibrate plan` read back from its directory.
struct CalibrationPlanFiles {
  std::string directory;
  std::string method;                 ///< as summary.json states it
  std::vector<std::string> pose_ids;  ///< per planned pose
  std::vector<Pose> poses;            ///< the planned poses, completed by the machine's mechanism
  std::vector<int> lines;             ///< per planned pose: its line in plan.csv
  CalibrationInstrument instrument;   ///< as summary.json states it (a fixture file's path resolved)
  calibration::MeasurementSetup setup;
  /// Where plan.csv's readings differ from this machine's inverse kinematics of its poses (a plan made for
  /// another geometry of the same type, or before a calibration): the poses are used as they are.
  std::vector<std::string> warnings;
};

/// DIR/plan.csv and DIR/summary.json read for `machine`. Errors (bad_input, or io for a file that cannot be
/// read) name the file: a missing or malformed file, a plan made for another machine type (other pose
/// columns, angle convention or calibration parameters) or another actuator count, a planned pose this
/// machine cannot reach, a fixture file that is not there or has another number of targets.
Result<CalibrationPlanFiles> read_calibration_plan(const Machine& machine, const std::string& directory);

/// The tool-point error predicted after measuring a plan, at any pose: Σ of the plan (once) and G at the
/// pose. Immutable once made: at() may be called from several threads at once.
class CalibratedErrorPrediction {
 public:
  /// Σ of measuring `plan` with `setup` on `machine`'s calibration model, and the model's stepped copies
  /// for G. Fails where the model cannot reach a planned pose or has no parameters.
  static Result<CalibratedErrorPrediction> make(const Machine& machine, const std::vector<Pose>& plan,
                                                const calibration::MeasurementSetup& setup);

  /// sqrt(trace(G·Σ·Gᵀ)) at `pose` (mm), as calibration::predict_plan gives it for a held-out pose. Fails
  /// where the pose is out of reach or a stepped model has no forward solution there.
  Result<double> at(const Pose& pose) const;

  const calibration::Identifiability& identifiability() const { return identifiability_; }

 private:
  calibration::Identifiability identifiability_;
  calibration::ToolSensitivityModel sensitivity_;
};

/// The plan read back and the map's function for its layer.
struct CalibrationWorkspaceLayer {
  CalibrationPlanFiles plan;
  std::shared_ptr<const CalibratedErrorPrediction> prediction;
  /// For workspace::WorkspaceMapOptions::calibrated_error: prediction->at(pose), NaN (an empty cell) where
  /// it fails. Safe to call concurrently.
  workspace::CalibratedErrorAtPose error_at_pose;
};

/// The layer for the plan in `directory` on `machine` (read_calibration_plan, then the prediction).
Result<CalibrationWorkspaceLayer> calibration_workspace_layer(const Machine& machine,
                                                              const std::string& directory);

}  // namespace pkm::pipeline
