#pragma once
// Forward kinematics of a rigid platform held by legs: damped Newton on the pose, warm-started.
//
// The unknown is the pose itself (position of the tool point, rotation matrix). Each iteration solves
//   J · (δp, δω) = −f,   f_j = q_j(B_j) − q_j^target,   B_j = p + R·b'_j,
// with J_j = [g_jᵀ, (R b'_j × g_j)ᵀ] and g_j = ∂q_j/∂B_j, and updates p += δp, R = exp([δω]×)·R. Updating the
// rotation on the manifold (not the angles) keeps convergence quadratic at any tilt; LinuxCNC's genhexkins
// subtracts the angular step from roll/pitch/yaw and is only linear away from zero tilt (anchors.md).
// A backtracking line search on |f| makes cold starts robust; the Jacobian's reciprocal condition number is
// checked before every solve, so a singular pose is reported, not hidden (STYLE habit 5).
//
// `Legs` provides:
//   int leg_count() const;
//   const Eigen::Vector3d& platform_joint(int j) const;                 // tool frame, mm
//   bool leg_value(int j, const Eigen::Vector3d& joint_base, double& q, Eigen::Vector3d& dq_dB) const;
//        // false when no actuator value reaches that joint position
// Nothing here allocates.
#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

#include "core/rotation.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

/// Actuator residuals and twist Jacobian of a leg platform at one pose (rows = legs; columns = δp then δω).
struct PlatformState {
  ActuatorVector residual;
  JacobianMatrix jacobian;  // n × 6 (rotating) or n × 3 (translating platform)
  bool reachable = true;
};

template <class Legs>
bool evaluate_platform(const Legs& legs, const Pose& pose, const ActuatorVector& target, bool rotates,
                       PlatformState& state) {
  const int n = legs.leg_count();
  state.residual.resize(n);
  state.jacobian.resize(n, rotates ? 6 : 3);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d arm = pose.rotation * legs.platform_joint(j);
    const Eigen::Vector3d joint = arm + pose.position_mm;
    double q = 0.0;
    Eigen::Vector3d g;
    if (!legs.leg_value(j, joint, q, g)) {
      state.reachable = false;
      return false;
    }
    state.residual[j] = q - target[j];
    state.jacobian.template block<1, 3>(j, 0) = g.transpose();
    if (rotates) state.jacobian.template block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
  state.reachable = true;
  return true;
}

/// Applies a step (δp, δω) to a pose; δω rotates about the base axes through the tool point.
inline Pose step_pose(const Pose& pose, const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>& step, bool rotates) {
  Pose out;
  out.position_mm = pose.position_mm + step.template head<3>();
  out.rotation = rotates ? Eigen::Matrix3d(rotation_from_rotation_vector(step.template tail<3>()) * pose.rotation)
                         : pose.rotation;
  return out;
}

template <class Legs>
Result<FkSolution> solve_platform_fk(const Legs& legs, bool rotates, const ActuatorVector& target,
                                     const Pose& guess, const FkOptions& options) {
  using Step = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  constexpr int kMaxHalvings = 30;

  Pose pose = guess;
  PlatformState state;
  if (!evaluate_platform(legs, pose, target, rotates, state)) {
    return make_error(ErrorCode::unreachable, "forward kinematics: the start guess is outside the reachable space");
  }
  double norm = state.residual.norm();
  double last_rcond = -1.0;  // of the Jacobian at the previous iterate; < 0 before the first solve
  for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
    const double max_abs = state.residual.cwiseAbs().maxCoeff();
    if (max_abs <= options.tolerance_mm) {
      // A solution at a singular configuration is reported, not returned: its neighbourhood is not unique.
      if (last_rcond < 0) last_rcond = Eigen::PartialPivLU<JacobianMatrix>(state.jacobian).rcond();
      if (!(last_rcond >= options.min_rcond)) {
        return make_error(ErrorCode::singular,
                          "forward kinematics: these actuator values put the mechanism in a singular configuration");
      }
      return FkSolution{pose, iteration, max_abs, 0};
    }
    if (iteration == options.max_iterations) break;
    const Eigen::PartialPivLU<JacobianMatrix> lu(state.jacobian);
    last_rcond = lu.rcond();
    if (!(last_rcond >= options.min_rcond)) {
      return make_error(ErrorCode::singular,
                        "forward kinematics: the Jacobian is singular on the way to a solution "
                        "(the actuator values may lie at a singular configuration)");
    }
    const Step full_step = lu.solve(-state.residual);
    double fraction = 1.0;
    bool accepted = false;
    PlatformState trial_state;
    for (int halving = 0; halving < kMaxHalvings; ++halving, fraction *= 0.5) {
      const Pose trial = step_pose(pose, fraction * full_step, rotates);
      if (!evaluate_platform(legs, trial, target, rotates, trial_state)) continue;
      const double trial_norm = trial_state.residual.norm();
      if (trial_norm < norm || trial_norm <= options.tolerance_mm) {
        pose = trial;
        state = trial_state;
        norm = trial_norm;
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
  }
  return make_error(ErrorCode::not_converged,
                    "forward kinematics did not converge within " + std::to_string(options.max_iterations) +
                        " iterations (residual " + std::to_string(state.residual.cwiseAbs().maxCoeff()) +
                        " mm); give a guess closer to the solution");
}

}  // namespace pkm
