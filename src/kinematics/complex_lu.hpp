#pragma once
// LU with partial pivoting of a small fixed-size complex matrix, for the path tracker's many 8×8 solves.
// Eigen's PartialPivLU runs its generic blocked code on a fixed 8×8 complex matrix, and std::complex's
// operator* goes through the C99 NaN/Inf rules (a library call per product unless the whole build uses
// -fcx-limited-range); the products here are written out. Inputs are finite (the tracker checks), so the
// Annex G cases cannot arise. No allocation.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <complex>

namespace pkm {

namespace complex_arithmetic {
inline std::complex<double> mul(std::complex<double> a, std::complex<double> b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}
inline std::complex<double> reciprocal(std::complex<double> a) {
  const double n = a.real() * a.real() + a.imag() * a.imag();
  return {a.real() / n, -a.imag() / n};
}
inline double abs2(std::complex<double> a) {
  return a.real() * a.real() + a.imag() * a.imag();
}
}  // namespace complex_arithmetic

template <int N>
class ComplexLu {
 public:
  using Matrix = Eigen::Matrix<std::complex<double>, N, N>;
  using Vector = Eigen::Matrix<std::complex<double>, N, 1>;

  /// Factorises `m`; false when a pivot is exactly zero (the matrix is singular).
  bool compute(const Matrix& m) {
    using namespace complex_arithmetic;
    lu_ = m;
    double largest = 0.0, smallest = INFINITY;
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      double best = abs2(lu_(k, k));
      for (int i = k + 1; i < N; ++i) {
        const double a = abs2(lu_(i, k));
        if (a > best) {
          best = a;
          pivot = i;
        }
      }
      permutation_[k] = pivot;
      if (pivot != k) lu_.row(k).swap(lu_.row(pivot));
      largest = std::max(largest, best);
      smallest = std::min(smallest, best);
      if (best == 0.0) {
        pivot_ratio_ = 0.0;
        return false;
      }
      inverse_pivot_[k] = reciprocal(lu_(k, k));
      for (int i = k + 1; i < N; ++i) {
        const std::complex<double> factor = mul(lu_(i, k), inverse_pivot_[k]);
        lu_(i, k) = factor;
        for (int j = k + 1; j < N; ++j) lu_(i, j) -= mul(factor, lu_(k, j));
      }
    }
    pivot_ratio_ = std::sqrt(smallest / largest);
    return true;
  }

  Vector solve(const Vector& b) const {
    using namespace complex_arithmetic;
    Vector x = b;
    for (int k = 0; k < N; ++k) {
      if (permutation_[k] != k) std::swap(x[k], x[permutation_[k]]);
    }
    for (int i = 1; i < N; ++i) {
      for (int j = 0; j < i; ++j) x[i] -= mul(lu_(i, j), x[j]);
    }
    for (int i = N - 1; i >= 0; --i) {
      for (int j = i + 1; j < N; ++j) x[i] -= mul(lu_(i, j), x[j]);
      x[i] = mul(x[i], inverse_pivot_[i]);
    }
    return x;
  }

  /// min |pivot| / max |pivot|: ≈ 0 for a (nearly) singular matrix.
  double pivot_ratio() const { return pivot_ratio_; }

 private:
  Matrix lu_;
  std::array<int, N> permutation_{};
  std::array<std::complex<double>, N> inverse_pivot_{};
  double pivot_ratio_ = 0.0;
};

}  // namespace pkm
