#pragma once
// Forward kinematics of a rigid platform held by legs: damped Newton on the pose, warm-started.
//
// The unknown is the pose itself (position of the tool point, rotation matrix). Each iteration solves
//   J · (δp, δω) = −f,   f_j = q_j(B_j) − q_j^target,   B_j = p + R·b'_j,
// with J_j = [g_jᵀ, (R b'_j × g_j)ᵀ] and g_j = ∂q_j/∂B_j, and updates p += δp, R = exp([δω]×)·R. Updating the
// rotation on the manifold (not the angles) keeps convergence quadratic at any tilt; LinuxCNC's genhexkins
// subtracts the angular step from roll/pitch/yaw and is only linear away from zero tilt (anchors.md).
// A backtracking line search on |f| makes cold starts robust; the Jacobian's reciprocal condition number is
// checked at every factorisation (pivot ratio, fixed_lu.hpp), so a singular pose is reported, not hidden
// (STYLE habit 5).
//
// `Legs` provides:
//   int leg_count() const;
//   const Eigen::Vector3d& platform_joint(int j) const;                 // tool frame, mm
//   bool leg_value(int j, const Eigen::Vector3d& joint_base, double& q, Eigen::Vector3d& dq_dB) const;
//        // false when no actuator value reaches that joint position
// and may provide, for residual-only evaluations that need no gradient (saves divisions on the hot path):
//   bool leg_position(int j, const Eigen::Vector3d& joint_base, double& q) const;
// A rotating platform has 6 legs, a translating one (orientation held by parallelograms) 3. All matrices are
// fixed-size: nothing here allocates.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/result.hpp"
#include "core/rotation.hpp"
#include "kinematics/actuator_vector.hpp"
#include "kinematics/fixed_lu.hpp"
#include "kinematics/fk_solution.hpp"

namespace pkm {

/// What the solver saw on the way, for assembly-mode checks without extra work: det J at the guess (first
/// factorisation) and at the last factorised iterate (within one converging step of the solution).
struct FkDiagnostics {
  double guess_determinant = 0.0;
  double final_determinant = 0.0;
};

/// Why the platform solver failed, as data: the servo-loop form (Mechanism::forward_warm_quiet) reports it
/// without building a message; platform_fk_error() words it for everyone else.
struct PlatformFkFailure {
  enum class Kind { start_unreachable, singular_solution, singular_path, not_converged };
  Kind kind = Kind::not_converged;
  double residual_mm = 0.0;  ///< max |residual| where Newton stopped (not_converged)
  ErrorCode code() const {
    switch (kind) {
      case Kind::start_unreachable:
        return ErrorCode::unreachable;
      case Kind::singular_solution:
      case Kind::singular_path:
        return ErrorCode::singular;
      case Kind::not_converged:
        break;
    }
    return ErrorCode::not_converged;
  }
};

/// exp([ω]×)·R = R + a·(ω × R) + b·(ω × (ω × R)), column by column (Rodrigues), without forming matrices:
/// the on-manifold update of the FK hot path.
inline Eigen::Matrix3d rotate_by(const Eigen::Vector3d& omega_rad, const Eigen::Matrix3d& rotation) {
  const RodriguesCoefficients c = rodrigues_coefficients(omega_rad.norm());
  Eigen::Matrix3d out;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d once = omega_rad.cross(rotation.col(k));
    out.col(k) = rotation.col(k) + c.a * once + c.b * omega_rad.cross(once);
  }
  return out;
}

/// Preallocated state carried from one FK call to the next along a path (Pinocchio's model/data split): the
/// last factorisation of the Jacobian. Along a path the solution moves a fraction of a millimetre per call,
/// so the previous factorisation serves as a chord-Newton matrix and most calls need no factorisation at all.
/// It also keeps the last four solutions: when the caller's guess is the last solution (it is following a
/// path), the start is extrapolated from them (cubic in position, quadratic in the rotation increment), which
/// puts it within about 1e-9 mm of the solution on a smooth path sampled at a servo rate, so one chord step
/// converges.
template <int N>
struct PlatformFkWorkspace {
  FixedLu<N> lu;
  bool valid = false;
  Pose last_solution;
  Eigen::Vector3d position_history_mm[3];  ///< positions one, two and three solutions before the last
  /// Base-frame rotation vectors between consecutive solutions, newest first.
  Eigen::Vector3d rotation_increments[3];
  int solutions_kept = 0;       ///< 0 … 4 (saturates)
  int last_solution_mode = -1;  ///< the mechanism's assembly-mode label of last_solution (-1: unknown)

  void reset() {
    valid = false;
    solutions_kept = 0;
    last_solution_mode = -1;
  }
  bool continues_path(const Pose& guess) const {
    return solutions_kept > 0 && guess.position_mm == last_solution.position_mm &&
           guess.rotation == last_solution.rotation;
  }
  /// Records a new solution of the path.
  void push(const Pose& solution) {
    if (solutions_kept > 0) {
      // Small-angle rotation vector of D = R_new·R_lastᵀ from its skew part (exact to O(θ³), enough for a
      // prediction); only the six off-diagonal entries are formed.
      const Eigen::Matrix3d& n = solution.rotation;
      const Eigen::Matrix3d& l = last_solution.rotation;
      auto d = [&](int i, int k) { return n.row(i).dot(l.row(k)); };
      for (int k = 2; k > 0; --k) {
        rotation_increments[k] = rotation_increments[k - 1];
        position_history_mm[k] = position_history_mm[k - 1];
      }
      rotation_increments[0] = 0.5 * Eigen::Vector3d(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
      position_history_mm[0] = last_solution.position_mm;
    }
    last_solution = solution;
    solutions_kept = solutions_kept < 4 ? solutions_kept + 1 : 4;
  }
};

/// The start pose: the guess, or its extrapolation when the guess continues the workspace's path.
template <int N>
Pose predicted_start(const PlatformFkWorkspace<N>& workspace, const Pose& guess) {
  if (workspace.solutions_kept < 2 || !workspace.continues_path(guess)) return guess;
  const Eigen::Vector3d& p0 = guess.position_mm;
  const Eigen::Vector3d* p = workspace.position_history_mm;
  const Eigen::Vector3d* v = workspace.rotation_increments;
  Pose start;
  Eigen::Vector3d increment;
  switch (workspace.solutions_kept) {
    case 2:  // linear
      start.position_mm = 2.0 * p0 - p[0];
      increment = v[0];
      break;
    case 3:  // quadratic
      start.position_mm = 3.0 * p0 - 3.0 * p[0] + p[1];
      increment = 2.0 * v[0] - v[1];
      break;
    default:  // cubic in position, quadratic in the increment
      start.position_mm = 4.0 * p0 - 6.0 * p[0] + 4.0 * p[1] - p[2];
      increment = 3.0 * v[0] - 3.0 * v[1] + v[2];
      break;
  }
  // R_next = exp([increment]×)·R_last; then re-orthonormalised (Gram–Schmidt), because Newton steps cannot
  // remove a shear the model does not contain (a deformed platform can still fit the strut lengths), so
  // round-off must not accumulate along a path.
  Eigen::Matrix3d r = rotate_by(increment, guess.rotation);
  r.col(0).normalize();
  r.col(1) -= r.col(0).dot(r.col(1)) * r.col(0);
  r.col(1).normalize();
  r.col(2) = r.col(0).cross(r.col(1));
  start.rotation = r;
  return start;
}

namespace detail {

/// Residuals f_j = q_j(B_j) − target_j at a pose; false when a leg cannot reach its joint.
template <int N, class Legs>
bool evaluate_residual(const Legs& legs, const Pose& pose, const ActuatorVector& target,
                       Eigen::Matrix<double, N, 1>& residual) {
  for (int j = 0; j < N; ++j) {
    const Eigen::Vector3d joint = pose.rotation * legs.platform_joint(j) + pose.position_mm;
    double q = 0.0;
    if constexpr (requires { legs.leg_position(j, joint, q); }) {
      if (!legs.leg_position(j, joint, q)) return false;
    } else {
      Eigen::Vector3d g;
      if (!legs.leg_value(j, joint, q, g)) return false;
    }
    residual[j] = q - target[j];
  }
  return true;
}

/// Twist Jacobian rows [g_jᵀ, (R b'_j × g_j)ᵀ] at a reachable pose (only needed when factorising).
template <int N, class Legs>
void evaluate_jacobian(const Legs& legs, const Pose& pose, Eigen::Matrix<double, N, N>& jacobian) {
  for (int j = 0; j < N; ++j) {
    const Eigen::Vector3d arm = pose.rotation * legs.platform_joint(j);
    double q = 0.0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    legs.leg_value(j, arm + pose.position_mm, q, g);
    jacobian.template block<1, 3>(j, 0) = g.transpose();
    if constexpr (N == 6) jacobian.template block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
}

template <int N>
Pose step_pose(const Pose& pose, const Eigen::Matrix<double, N, 1>& step) {
  Pose out;
  out.position_mm = pose.position_mm + step.template head<3>();
  if constexpr (N == 6) {
    out.rotation = rotate_by(step.template tail<3>(), pose.rotation);
  } else {
    out.rotation = pose.rotation;
  }
  return out;
}

/// The words of a failure, as forward() reports it.
Error platform_fk_error(const PlatformFkFailure& failure, const FkOptions& options);

/// The Newton step −J⁻¹·r from `lu`, halved until the residual shrinks (or meets the tolerance): true with
/// `pose`, `residual` and `norm` moved there, and `contracted_well` when the full step shrank the residual to
/// `chord_contraction` of what it was or less; false when no fraction of the step helps.
template <int N, class Legs>
bool backtracking_newton_step(const Legs& legs, const ActuatorVector& target, const FixedLu<N>& lu,
                              double tolerance_mm, double chord_contraction, Pose& pose,
                              Eigen::Matrix<double, N, 1>& residual, double& norm, bool& contracted_well) {
  using Vector = Eigen::Matrix<double, N, 1>;
  constexpr int kMaxHalvings = 30;
  const Vector full_step = lu.solve(-residual);
  Vector trial_residual;
  double fraction = 1.0;
  for (int halving = 0; halving < kMaxHalvings; ++halving, fraction *= 0.5) {
    const Pose trial = step_pose<N>(pose, Vector(fraction * full_step));
    if (!evaluate_residual<N>(legs, trial, target, trial_residual)) continue;
    const double trial_norm = trial_residual.norm();
    if (trial_norm < norm || trial_norm <= tolerance_mm) {
      contracted_well = halving == 0 && trial_norm <= chord_contraction * norm;
      pose = trial;
      residual = trial_residual;
      norm = trial_norm;
      return true;
    }
  }
  return false;
}

/// Newton on the platform pose from `guess`: true with `out`, or false with `failure` (no message, no
/// allocation: the servo loop's form).
template <int N, class Legs>
bool solve_platform_fk_quiet(const Legs& legs, const ActuatorVector& target, const Pose& guess,
                             const FkOptions& options, FkDiagnostics* diagnostics,
                             PlatformFkWorkspace<N>* workspace, FkSolution& out, PlatformFkFailure& failure) {
  auto fail = [&failure](PlatformFkFailure::Kind kind) {
    failure.kind = kind;
    return false;
  };
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  // A step made with an older factorisation (chord Newton) is kept while it shrinks the residual at least
  // this much; along a path the guess is within a fraction of a millimetre, one factorisation then serves
  // every step.
  constexpr double kChordContraction = 0.1;
  // A carried-over factorisation is refreshed at the solution when its steps contracted worse than this, so
  // that it does not go stale along a long path.
  constexpr double kRefreshContraction = 1e-3;
  double worst_chord_ratio = 0.0;

  Pose pose = workspace ? predicted_start(*workspace, guess) : guess;
  Vector residual;
  Matrix jacobian;
  bool reachable = evaluate_residual<N>(legs, pose, target, residual);
  if (!reachable && workspace) {
    pose = guess;  // the extrapolation left the reachable space: start from the guess itself
    reachable = evaluate_residual<N>(legs, pose, target, residual);
  }
  if (!reachable) return fail(PlatformFkFailure::Kind::start_unreachable);
  double norm = residual.norm();
  FixedLu<N> local_lu;
  FixedLu<N>& lu = workspace ? workspace->lu : local_lu;  // factorised in place: no copies on the hot path
  bool factorised = false;                                // lu holds some iterate's Jacobian
  bool lu_is_current = false;                             // ... and that iterate is `pose`
  if (workspace && workspace->valid) {
    factorised = true;
    workspace->valid = false;  // until this call succeeds: every error return leaves it invalid
    if (diagnostics) diagnostics->guess_determinant = diagnostics->final_determinant = lu.determinant();
  }
  auto keep = [&] {
    if (!workspace) return;
    if (!factorised || worst_chord_ratio > kRefreshContraction) {
      evaluate_jacobian<N>(legs, pose, jacobian);
      lu.compute(jacobian);
    }
    workspace->valid = lu.pivot_ratio() >= options.min_rcond;
    workspace->push(pose);
  };
  auto factorise = [&](int iteration) -> bool {
    evaluate_jacobian<N>(legs, pose, jacobian);
    lu.compute(jacobian);
    factorised = lu_is_current = true;
    if (diagnostics) {
      diagnostics->final_determinant = lu.determinant();
      if (iteration == 0) diagnostics->guess_determinant = diagnostics->final_determinant;
    }
    return lu.pivot_ratio() >= options.min_rcond;
  };
  for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
    const double max_abs = residual.cwiseAbs().maxCoeff();
    if (max_abs <= options.tolerance_mm) {
      // A solution at a singular configuration is reported, not returned: its neighbourhood is not unique.
      if (!factorised && !factorise(0)) return fail(PlatformFkFailure::Kind::singular_solution);
      if (!(lu.pivot_ratio() >= options.min_rcond)) return fail(PlatformFkFailure::Kind::singular_solution);
      keep();
      out = FkSolution{pose, iteration, max_abs, 0};
      return true;
    }
    if (iteration == options.max_iterations) break;
    if (!factorised && !factorise(iteration)) return fail(PlatformFkFailure::Kind::singular_path);
    Vector trial_residual;
    // Chord step with the factorisation we have.
    if (!lu_is_current) {
      const Pose trial = step_pose<N>(pose, Vector(lu.solve(-residual)));
      if (evaluate_residual<N>(legs, trial, target, trial_residual)) {
        const double trial_norm = trial_residual.norm();
        if (trial_norm <= kChordContraction * norm || trial_norm <= options.tolerance_mm) {
          if (trial_norm > options.tolerance_mm)
            worst_chord_ratio = std::max(worst_chord_ratio, trial_norm / norm);
          pose = trial;
          residual = trial_residual;
          norm = trial_norm;
          continue;
        }
      }
      if (!factorise(iteration)) return fail(PlatformFkFailure::Kind::singular_path);
    }
    // Newton step from a fresh factorisation, with backtracking; the factorisation is kept for chord steps
    // only when the full step contracted well.
    bool contracted_well = false;
    if (!backtracking_newton_step<N>(legs, target, lu, options.tolerance_mm, kChordContraction, pose,
                                     residual, norm, contracted_well))
      break;
    lu_is_current = false;
    if (!contracted_well) factorised = false;
  }
  if (workspace) workspace->reset();
  failure.residual_mm = residual.cwiseAbs().maxCoeff();
  return fail(PlatformFkFailure::Kind::not_converged);
}

template <int N, class Legs>
Result<FkSolution> solve_platform_fk_fixed(const Legs& legs, const ActuatorVector& target, const Pose& guess,
                                           const FkOptions& options, FkDiagnostics* diagnostics,
                                           PlatformFkWorkspace<N>* workspace = nullptr) {
  FkSolution solution;
  PlatformFkFailure failure;
  if (solve_platform_fk_quiet<N>(legs, target, guess, options, diagnostics, workspace, solution, failure)) {
    return solution;
  }
  return platform_fk_error(failure, options);
}

}  // namespace detail

/// FK of a platform on 6 legs (rotates = true) or a translating platform on 3 legs (rotates = false).
template <class Legs>
Result<FkSolution> solve_platform_fk(const Legs& legs, bool rotates, const ActuatorVector& target,
                                     const Pose& guess, const FkOptions& options,
                                     FkDiagnostics* diagnostics = nullptr) {
  if (rotates && legs.leg_count() == 6) {
    return detail::solve_platform_fk_fixed<6>(legs, target, guess, options, diagnostics);
  }
  if (!rotates && legs.leg_count() == 3) {
    return detail::solve_platform_fk_fixed<3>(legs, target, guess, options, diagnostics);
  }
  return make_error(ErrorCode::unsupported,
                    "platform forward kinematics needs 6 legs (rotating) or 3 (translating)");
}

}  // namespace pkm
