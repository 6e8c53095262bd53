#pragma once
// Damped Newton with backtracking for small square systems F(x) = 0 (the FK of reduced-DOF mechanisms: the
// tricept in the tool point, the tripod in its three joint angles). Fixed-size, no allocation.
//
// `evaluate(x, f, J)` fills the residual and its Jacobian and returns false when x is outside the domain.
// `to_mm` converts residual entries into millimetres for the tolerance test and the line search, so the
// stopping rule is always "max error ≤ options.tolerance_mm".
#include <Eigen/Core>
#include <Eigen/LU>

#include "kinematics/fk_solution.hpp"

namespace pkm {

enum class NewtonStatus {
  converged,
  start_outside,
  singular_on_the_way,
  singular_at_solution,
  not_converged
};

template <int N>
struct NewtonState {
  Eigen::Matrix<double, N, 1> x;
  Eigen::Matrix<double, N, 1> f;
  Eigen::Matrix<double, N, N> jacobian;
  int iterations = 0;
  double residual_mm = 0.0;  ///< max |f ∘ to_mm|
};

template <int N, class Evaluate>
NewtonStatus damped_newton(Evaluate&& evaluate, const Eigen::Matrix<double, N, 1>& start,
                           const Eigen::Matrix<double, N, 1>& to_mm, const FkOptions& options,
                           NewtonState<N>& state) {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  constexpr int kMaxHalvings = 30;
  state.x = start;
  state.iterations = 0;
  if (!evaluate(state.x, state.f, state.jacobian)) return NewtonStatus::start_outside;
  double norm = state.f.cwiseProduct(to_mm).norm();
  for (;; ++state.iterations) {
    state.residual_mm = state.f.cwiseProduct(to_mm).cwiseAbs().maxCoeff();
    if (state.residual_mm <= options.tolerance_mm) {
      // A solution at a singular configuration is reported, not returned: its neighbourhood is not unique.
      return Eigen::PartialPivLU<Matrix>(state.jacobian).rcond() >= options.min_rcond
                 ? NewtonStatus::converged
                 : NewtonStatus::singular_at_solution;
    }
    if (state.iterations == options.max_iterations) return NewtonStatus::not_converged;
    const Eigen::PartialPivLU<Matrix> lu(state.jacobian);
    if (!(lu.rcond() >= options.min_rcond)) return NewtonStatus::singular_on_the_way;
    const Vector step = lu.solve(-state.f);
    bool accepted = false;
    double fraction = 1.0;
    for (int halving = 0; halving < kMaxHalvings && !accepted; ++halving, fraction *= 0.5) {
      const Vector trial = state.x + fraction * step;
      Vector trial_f;
      Matrix trial_jacobian;
      if (!evaluate(trial, trial_f, trial_jacobian)) continue;
      const double trial_norm = trial_f.cwiseProduct(to_mm).norm();
      if (trial_norm < norm || trial_norm <= options.tolerance_mm) {
        state.x = trial;
        state.f = trial_f;
        state.jacobian = trial_jacobian;
        norm = trial_norm;
        accepted = true;
      }
    }
    if (!accepted) return NewtonStatus::not_converged;
  }
}

}  // namespace pkm
