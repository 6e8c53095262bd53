#pragma once
// LU factorisation with partial pivoting for small fixed-size systems (3×3, 6×6) on the FK hot path.
// Eigen's PartialPivLU goes through a generic blocked kernel and its rcond() estimate costs more than the
// factorisation itself at these sizes (profiled: ~5 000 instructions of a 10 000-instruction FK solve).
// Singularity test: the ratio of the smallest to the largest pivot, a cheap stand-in for the reciprocal
// condition number that is exactly 0 for a singular matrix.
#include <Eigen/Core>
#include <cmath>

namespace pkm {

template <int N>
class FixedLu {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;

  void compute(const Matrix& a) {
    lu_ = a;
    sign_ = 1.0;
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      double best = std::abs(lu_(k, k));
      for (int i = k + 1; i < N; ++i) {
        const double v = std::abs(lu_(i, k));
        if (v > best) {
          best = v;
          pivot = i;
        }
      }
      permutation_[k] = pivot;
      if (pivot != k) {
        lu_.row(k).swap(lu_.row(pivot));
        sign_ = -sign_;
      }
      const double diagonal = lu_(k, k);
      if (diagonal == 0.0) continue;  // singular; pivot_ratio() reports it
      for (int i = k + 1; i < N; ++i) {
        const double factor = lu_(i, k) / diagonal;
        lu_(i, k) = factor;
        for (int j = k + 1; j < N; ++j) lu_(i, j) -= factor * lu_(k, j);
      }
    }
  }

  /// min |U_kk| / max |U_kk|; 0 for a singular matrix.
  double pivot_ratio() const {
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < N; ++k) {
      const double v = std::abs(lu_(k, k));
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    return hi > 0.0 ? lo / hi : 0.0;
  }

  double determinant() const {
    double d = sign_;
    for (int k = 0; k < N; ++k) d *= lu_(k, k);
    return d;
  }

  Vector solve(const Vector& b) const {
    Vector x = b;
    for (int k = 0; k < N; ++k) {
      if (permutation_[k] != k) std::swap(x[k], x[permutation_[k]]);
    }
    for (int i = 1; i < N; ++i) {
      for (int j = 0; j < i; ++j) x[i] -= lu_(i, j) * x[j];
    }
    for (int i = N - 1; i >= 0; --i) {
      for (int j = i + 1; j < N; ++j) x[i] -= lu_(i, j) * x[j];
      x[i] /= lu_(i, i);
    }
    return x;
  }

 private:
  Matrix lu_ = Matrix::Zero();
  int permutation_[N] = {};
  double sign_ = 1.0;
};

}  // namespace pkm
