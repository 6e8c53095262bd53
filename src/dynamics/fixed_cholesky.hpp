#pragma once
// Solve of a small symmetric positive-definite system (the 6 × 6 mass matrix on the elastic model's
// right-hand side, ~15 000 solves per simulated second). As kinematics/fixed_lu.hpp says of LU: Eigen's LLT
// at this size runs through generic unblocked kernels and triangular solves that cost several times the
// arithmetic (profiled: a fifth of the right-hand side). Here a = L D Lᵀ (no square roots) in plain loops
// over a fixed size, and one division per pivot.
#include <Eigen/Core>

namespace pkm::dynamics {

/// Solves a x = b for symmetric positive-definite a (its lower triangle is read); false (x unspecified) when
/// a pivot is not positive: a is not positive definite. Right-looking: each pivot's updates of the remaining
/// lower triangle, and each solve's updates of the remaining right-hand side, are independent of one another,
/// so they overlap in the processor instead of queueing on one running sum.
/// This one factors `f` in place (it becomes L, unit lower strictly below the diagonal, and D on it): for a
/// workspace's matrix that is not needed afterwards, without a copy.
template <int N>
bool cholesky_solve_in_place(Eigen::Matrix<double, N, N>& f, const Eigen::Matrix<double, N, 1>& b,
                             Eigen::Matrix<double, N, 1>& x) {
  Eigen::Matrix<double, N, 1> inverse_d;
#pragma GCC unroll 8
  for (int k = 0; k < N; ++k) {
    const double d = f(k, k);
    if (!(d > 0.0)) return false;
    inverse_d[k] = 1.0 / d;
#pragma GCC unroll 8
    for (int j = k + 1; j < N; ++j) {
      const double l_jk = f(j, k) * inverse_d[k];
#pragma GCC unroll 8
      for (int i = j; i < N; ++i) f(i, j) -= f(i, k) * l_jk;  // a_ij − l_ik d_k l_jk, with f(i, k) = l_ik d_k
    }
#pragma GCC unroll 8
    for (int i = k + 1; i < N; ++i) f(i, k) *= inverse_d[k];
  }
  x = b;
#pragma GCC unroll 8
  for (int k = 0; k < N; ++k) {  // L y = b
#pragma GCC unroll 8
    for (int i = k + 1; i < N; ++i) x[i] -= f(i, k) * x[k];
  }
  for (int k = 0; k < N; ++k) x[k] *= inverse_d[k];  // D z = y
#pragma GCC unroll 8
  for (int k = N - 1; k >= 0; --k) {  // Lᵀ x = z
#pragma GCC unroll 8
    for (int i = 0; i < k; ++i) x[i] -= f(k, i) * x[k];
  }
  return true;
}

/// The same for an `a` that is kept; it may have run-time sizes (N × N at run time): it is read once, into
/// the fixed-size factors.
template <int N, class MatrixA>
bool cholesky_solve(const Eigen::MatrixBase<MatrixA>& a, const Eigen::Matrix<double, N, 1>& b,
                    Eigen::Matrix<double, N, 1>& x) {
  Eigen::Matrix<double, N, N> f = a;
  return cholesky_solve_in_place<N>(f, b, x);
}

}  // namespace pkm::dynamics
