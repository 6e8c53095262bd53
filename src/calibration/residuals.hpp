#pragma once
// The residuals of an identification (Smirnov 2019, eq. 175 generalised to least squares), one block per
// measured pose, each weighted so that its entries have unit variance:
//  - pose_inverse: a pose with ≥ 3 targets (not collinear) on a mechanism that controls all six coordinates.
//    The pose is fitted from the targets once (pose_fit.hpp, eqs. 173–174) and the residual is IK_θ(pose) −
//    reading per actuator, as in the dissertation's (175). Its weight is the pose fit's uncertainty carried
//    to the actuators: the residuals' covariance is C_L = J·C·Jᵀ (C the fit's 6 × 6 twist covariance, J =
//    ∂IK/∂twist at the nominal model), and the block is whitened by L⁻¹ with L·Lᵀ = C_L. To first order this
//    carries the targets' full information on θ, with no forward kinematics per evaluation.
//  - targets_forward: fewer than 3 targets at a pose, or a reduced-DOF mechanism (whose IK ignores the
//    dependent coordinates that the targets also measure): measured − (FK_θ(readings) applied to the target),
//    three rows per target, weight 1/σ.
//  - ballbar_forward: |FK_θ(readings) tool point − ball centre| − distance, weight 1/σ.
// Forward kinematics is warm-started from the previous solution of the same pose (the nominal one at first).
#include <Eigen/Core>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "io/measurements.hpp"
#include "machine/mechanism.hpp"

namespace pkm::calibration {

enum class ResidualForm { pose_inverse, targets_forward, ballbar_forward };

struct ResidualBlock {
  int pose = 0;  ///< index into MeasurementSet::poses
  ResidualForm form = ResidualForm::pose_inverse;
  int first_row = 0;
  int rows = 0;
  Eigen::MatrixXd whitening;  ///< rows × rows: weighted = whitening · raw
  Pose fitted_pose;           ///< pose_inverse: the pose fitted to the targets
  Pose commanded_pose;  ///< the nominal model's FK of the readings (noise-free: depends on the plan only)
};

struct ResidualOptions {
  /// Use the pose_inverse form where it applies (else every target pose goes through forward kinematics).
  bool pose_inverse_where_possible = true;
  /// Forward kinematics inside the residuals: tight, as finite differences divide its error by the step.
  FkOptions fk{1e-11, 60, 1e-13, true};
  /// Central-difference step over the scaled parameters (calibration_parameters.hpp), mm: small against the
  /// curvature of the residuals (|B − A| ≈ 600 mm: truncation ~ step²/L ≈ 1e-11), large against round-off
  /// (1e-16 · 600 mm / step ≈ 1e-10 relative).
  double derivative_step_mm = 1e-4;
};

class ResidualModel {
 public:
  /// Blocks for every measured pose of `data` on `nominal`, and the nominal poses (FK starts). Fails for a
  /// pose without observations, readings of the wrong size, an observation naming no target, a σ ≤ 0, or a
  /// pose whose forward kinematics has no solution on the nominal model (the message names the pose).
  static Result<ResidualModel> make(const Mechanism& nominal, const MeasurementSet& data,
                                    const ResidualOptions& options = {});

  int rows() const { return rows_; }
  const std::vector<ResidualBlock>& blocks() const { return blocks_; }
  const MeasurementSet& data() const { return data_; }
  const ResidualOptions& options() const { return options_; }
  /// The poses at the nominal model, one per measured pose: FK starts for evaluate().
  const std::vector<Pose>& start_poses() const { return start_poses_; }
  /// The same model with every pose_inverse block at its commanded pose instead of its fitted one. Its
  /// Jacobian depends on the plan alone, not on the measurement noise (the other forms' Jacobians never do):
  /// what a plan can identify is judged on it, so that noise cannot make a plan of identical poses look
  /// identifiable (identify.hpp).
  ResidualModel at_commanded_poses() const;
  /// How many blocks use each form.
  int count(ResidualForm form) const;

  /// The residuals at `mechanism` (the nominal with other parameter values): `raw` in mm (actuator, target
  /// coordinate or distance), `weighted` = whitened per block (may be null). `poses` holds one FK start per
  /// measured pose and receives the solutions. Fails, naming the pose, where IK or FK has no solution.
  Status evaluate(const Mechanism& mechanism, std::vector<Pose>& poses, Eigen::VectorXd& raw,
                  Eigen::VectorXd* weighted) const;

 private:
  MeasurementSet data_;
  ResidualOptions options_;
  std::vector<ResidualBlock> blocks_;
  std::vector<Pose> start_poses_;
  int rows_ = 0;
};

}  // namespace pkm::calibration
