#pragma once
// The path tracker's arithmetic (kinematics/stewart_homotopy.cpp) on pairs of doubles: the same equations,
// Jacobian, LU and Taylor coefficients as StewartSystem and ComplexLu<8> (which stay the reference the tests
// compare with), laid out so that every operation works on two complex numbers at once.
//
// Why: the tracker spends all its time in complex multiply–adds on 8×8 and 6-leg data. Written one complex
// number at a time they run at the scalar floating-point rate (one double per instruction); with the real and
// the imaginary parts in separate two-lane vectors (two legs, two rows of a column), each instruction does
// two, on the baseline x86-64 (SSE2) and AArch64 (NEON) alike, without -march flags. The layout:
// - legs in pairs: leg quantities are vectors over legs (2q, 2q + 1), q = 0, 1, 2;
// - an 8-vector (equations: legs 0–5, Study quadric, chart; unknowns: e0..e3, g0..g3) is 4 pairs;
// - the Jacobian is stored by columns, each column 4 pairs of rows, so that the LU's row operations and the
//   leg equations both fill and update whole pairs.
// GCC/Clang vector extensions (not intrinsics) keep it portable. Fixed sizes throughout: nothing allocates.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <type_traits>

#include "kinematics/stewart_system.hpp"

namespace pkm::stewart_lanes {

using Lane = double __attribute__((vector_size(16)));

/// Two complex numbers.
struct CLane {
  Lane re, im;
};

inline CLane operator+(CLane a, CLane b) {
  return {a.re + b.re, a.im + b.im};
}
inline CLane operator-(CLane a, CLane b) {
  return {a.re - b.re, a.im - b.im};
}
inline CLane operator*(double s, CLane a) {
  return {s * a.re, s * a.im};
}
inline CLane operator*(CLane a, CLane b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
/// Both lanes times one complex number.
inline CLane operator*(CLane a, Complex b) {
  return {a.re * b.real() - a.im * b.imag(), a.re * b.imag() + a.im * b.real()};
}
inline CLane broadcast(Complex b) {
  return {Lane{b.real(), b.real()}, Lane{b.imag(), b.imag()}};
}

/// 8 complex numbers in 4 pairs.
struct Vec8 {
  CLane pair[4];

  Complex get(int i) const { return {pair[i >> 1].re[i & 1], pair[i >> 1].im[i & 1]}; }
  void set(int i, Complex v) {
    pair[i >> 1].re[i & 1] = v.real();
    pair[i >> 1].im[i & 1] = v.imag();
  }
  static Vec8 of(const StudyPoint& x) {
    Vec8 v;
    for (int i = 0; i < 8; ++i) v.set(i, x[i]);
    return v;
  }
  StudyPoint point() const {
    StudyPoint x;
    for (int i = 0; i < 8; ++i) x[i] = get(i);
    return x;
  }
  double squared_norm() const {
    Lane sum = pair[0].re * pair[0].re + pair[0].im * pair[0].im;
    for (int q = 1; q < 4; ++q) sum += pair[q].re * pair[q].re + pair[q].im * pair[q].im;
    return sum[0] + sum[1];
  }
  double norm() const { return std::sqrt(squared_norm()); }
  Vec8& operator-=(const Vec8& b) {
    for (int q = 0; q < 4; ++q) pair[q] = pair[q] - b.pair[q];
    return *this;
  }
};

/// The 8×8 Jacobian by columns (unknowns), each column 4 pairs of rows (equations).
struct Mat8 {
  CLane column[8][4];
};

/// The six legs' parameters d_j, s_j, L_j² (kinematics/stewart_system.hpp) by pairs of legs.
struct Legs {
  CLane d[3][3];  ///< [component][pair]
  CLane s[3][3];
  CLane length_squared[3];

  static Legs of(const StewartParameters& p) {
    Legs legs;
    for (int j = 0; j < 6; ++j) {
      const int q = j >> 1, lane = j & 1;
      for (int c = 0; c < 3; ++c) {
        legs.d[c][q].re[lane] = p.d[j][c].real();
        legs.d[c][q].im[lane] = p.d[j][c].imag();
        legs.s[c][q].re[lane] = p.s[j][c].real();
        legs.s[c][q].im[lane] = p.s[j][c].imag();
      }
      legs.length_squared[q].re[lane] = p.length_squared[j].real();
      legs.length_squared[q].im[lane] = p.length_squared[j].imag();
    }
    return legs;
  }
  /// this + t·rate.
  Legs lerp_rate(const Legs& rate, double t) const {
    Legs out;
    for (int q = 0; q < 3; ++q) {
      for (int c = 0; c < 3; ++c) {
        out.d[c][q] = d[c][q] + t * rate.d[c][q];
        out.s[c][q] = s[c][q] + t * rate.s[c][q];
      }
      out.length_squared[q] = length_squared[q] + t * rate.length_squared[q];
    }
    return out;
  }
};

/// The leg quaternions y = M e of one pair of legs (leg_quaternion), e given as 4 complex numbers.
inline void leg_products(const Legs& p, int q, const Complex* e, CLane* y) {
  y[0] = p.d[0][q] * e[1] + p.d[1][q] * e[2] + p.d[2][q] * e[3];
  y[1] = p.s[2][q] * e[2] - p.s[1][q] * e[3] - p.d[0][q] * e[0];
  y[2] = p.s[0][q] * e[3] - p.s[2][q] * e[1] - p.d[1][q] * e[0];
  y[3] = p.s[1][q] * e[1] - p.s[0][q] * e[2] - p.d[2][q] * e[0];
}

inline Complex dot4(const Complex* a, const Complex* b) {
  using complex_arithmetic::mul;
  return mul(a[0], b[0]) + mul(a[1], b[1]) + mul(a[2], b[2]) + mul(a[3], b[3]);
}

/// The equations' values (when f is not null) and Jacobian at x, as StewartSystem::linearise.
inline void linearise(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f, Mat8& jx) {
  Complex e[4], g[4];
  for (int c = 0; c < 4; ++c) {
    e[c] = x.get(c);
    g[c] = x.get(4 + c);
  }
  const Complex gg = dot4(g, g), ee = dot4(e, e);
  for (int q = 0; q < 3; ++q) {
    CLane y[4];
    leg_products(p, q, e, y);
    const CLane g0 = broadcast(g[0]), g1 = broadcast(g[1]), g2 = broadcast(g[2]), g3 = broadcast(g[3]);
    if (f) {
      const CLane gy = y[0] * g[0] + y[1] * g[1] + y[2] * g[2] + y[3] * g[3];
      const CLane yy = y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3];
      f->pair[q] = 4.0 * (broadcast(gg) + gy) + yy - p.length_squared[q] * ee;
    }
    // ∂f/∂g = 8g + 4y;  ∂f/∂e = Mᵀw − 2L² e with w = 4g + 2y, Mᵀw = (−d·w_v, w0 d + s × w_v).
    jx.column[4][q] = 8.0 * g0 + 4.0 * y[0];
    jx.column[5][q] = 8.0 * g1 + 4.0 * y[1];
    jx.column[6][q] = 8.0 * g2 + 4.0 * y[2];
    jx.column[7][q] = 8.0 * g3 + 4.0 * y[3];
    const CLane w0 = 4.0 * g0 + 2.0 * y[0], w1 = 4.0 * g1 + 2.0 * y[1], w2 = 4.0 * g2 + 2.0 * y[2],
                w3 = 4.0 * g3 + 2.0 * y[3];
    const CLane l2 = 2.0 * p.length_squared[q];
    jx.column[0][q] = CLane{} - (p.d[0][q] * w1 + p.d[1][q] * w2 + p.d[2][q] * w3) - l2 * e[0];
    jx.column[1][q] = w0 * p.d[0][q] + p.s[1][q] * w3 - p.s[2][q] * w2 - l2 * e[1];
    jx.column[2][q] = w0 * p.d[1][q] + p.s[2][q] * w1 - p.s[0][q] * w3 - l2 * e[2];
    jx.column[3][q] = w0 * p.d[2][q] + p.s[0][q] * w2 - p.s[1][q] * w1 - l2 * e[3];
  }
  // Pair 3: the Study quadric eᵀg = 0 and the chart cᵀe = 1.
  if (f) {
    f->set(6, dot4(e, g));
    f->set(7, chart[0] * e[0] + chart[1] * e[1] + chart[2] * e[2] + chart[3] * e[3] - 1.0);
  }
  for (int c = 0; c < 4; ++c) {
    jx.column[c][3] = CLane{Lane{g[c].real(), chart[c].real()}, Lane{g[c].imag(), chart[c].imag()}};
    jx.column[4 + c][3] = CLane{Lane{e[c].real(), 0.0}, Lane{e[c].imag(), 0.0}};
  }
}

/// f(0), f(1), …, f(End − 1) with compile-time indices: the loops over the 8 rows and columns unrolled, so
/// that every lane index is a constant and the data stays in registers.
template <int Begin, int End, class F>
[[gnu::always_inline]] inline void static_for(F&& f) {
  if constexpr (Begin < End) {
    f(std::integral_constant<int, Begin>{});
    static_for<Begin + 1, End>(f);
  }
}

/// LU with partial pivoting of a Mat8, as ComplexLu<8>: L (unit, strictly lower) and U (strictly upper, the
/// diagonal kept as inverse pivots) in separate column arrays with zeros elsewhere, so that the solves update
/// whole pairs without masks.
class LaneLu {
 public:
  bool compute(const Mat8& m) {
    for (int c = 0; c < 8; ++c) {
      for (int q = 0; q < 4; ++q) {
        upper_[c][q] = m.column[c][q];
        lower_[c][q] = CLane{};
      }
    }
    largest_ = 0.0;
    smallest_ = INFINITY;
    bool regular = true;
    static_for<0, 8>([&](auto k) {
      if (regular) regular = eliminate<k>();
    });
    if (!regular) {
      pivot_ratio_ = 0.0;
      return false;
    }
    // U's columns keep only the rows above the diagonal (below it elimination left zeros up to rounding, and
    // the diagonal is in inverse_pivot_), cleared so that the back substitution can update whole pairs.
    static_for<0, 8>([&](auto c) {
      if constexpr (c % 2 == 1) {
        upper_[c][c / 2].re[1] = 0.0;
        upper_[c][c / 2].im[1] = 0.0;
      } else {
        upper_[c][c / 2] = CLane{};
      }
      for (int q = c / 2 + 1; q < 4; ++q) upper_[c][q] = CLane{};
    });
    // The row interchanges as one gather: row i of the permuted system is row row_of_[i] of the original.
    for (int i = 0; i < 8; ++i) row_of_[i] = i;
    for (int k = 0; k < 8; ++k) std::swap(row_of_[k], row_of_[permutation_[k]]);
    pivot_ratio_ = std::sqrt(smallest_ / largest_);
    return true;
  }

  Vec8 solve(const Vec8& b) const {
    Vec8 x;
    static_for<0, 8>([&](auto i) __attribute__((always_inline)) { x.set(i, b.get(row_of_[i])); });
    static_for<0, 7>([&](auto k) __attribute__((always_inline)) {
      const Complex xk = x.get(k);
      for (int q = (k + 1) / 2; q < 4; ++q) x.pair[q] = x.pair[q] - lower_[k][q] * xk;
    });
    static_for<0, 8>([&](auto kk) __attribute__((always_inline)) {
      constexpr int k = 7 - kk;
      const Complex xk = complex_arithmetic::mul(x.get(k), inverse_pivot_[k]);
      x.set(k, xk);
      for (int q = 0; q < (k + 1) / 2; ++q) x.pair[q] = x.pair[q] - upper_[k][q] * xk;
    });
    return x;
  }

  double pivot_ratio() const { return pivot_ratio_; }

 private:
  template <int K>
  bool eliminate() {
    int pivot = K;
    double best = abs2(upper_[K], K);
    for (int i = K + 1; i < 8; ++i) {
      const double v = abs2(upper_[K], i);
      if (v > best) {
        best = v;
        pivot = i;
      }
    }
    permutation_[K] = pivot;
    if (pivot != K) {
      for (int c = 0; c < 8; ++c) swap_rows(upper_[c], K, pivot);
      for (int c = 0; c < K; ++c) swap_rows(lower_[c], K, pivot);
    }
    largest_ = std::max(largest_, best);
    smallest_ = std::min(smallest_, best);
    if (best == 0.0) return false;
    const Complex pk = get(upper_[K], K);
    const Complex inverse = {pk.real() / best, -pk.imag() / best};
    inverse_pivot_[K] = inverse;
    // Multipliers of the rows below K; row K itself (lane 0 of its pair when K is even) gets none, so that
    // the update leaves it alone.
    constexpr int q0 = (K + 1) / 2;
    for (int q = q0; q < 4; ++q) lower_[K][q] = upper_[K][q] * inverse;
    if constexpr (K % 2 == 0) {
      lower_[K][q0].re[0] = 0.0;
      lower_[K][q0].im[0] = 0.0;
    }
    static_for<K + 1, 8>([&](auto j) {
      const Complex b = get(upper_[j], K);
      for (int q = q0; q < 4; ++q) upper_[j][q] = upper_[j][q] - lower_[K][q] * b;
    });
    return true;
  }

  static double abs2(const CLane* column, int i) {
    const double re = column[i >> 1].re[i & 1], im = column[i >> 1].im[i & 1];
    return re * re + im * im;
  }
  static Complex get(const CLane* column, int i) {
    return {column[i >> 1].re[i & 1], column[i >> 1].im[i & 1]};
  }
  static void set(CLane* column, int i, Complex v) {
    column[i >> 1].re[i & 1] = v.real();
    column[i >> 1].im[i & 1] = v.imag();
  }
  static void swap_rows(CLane* column, int a, int b) {
    const Complex va = get(column, a);
    set(column, a, get(column, b));
    set(column, b, va);
  }

  CLane lower_[8][4];
  CLane upper_[8][4];
  std::array<Complex, 8> inverse_pivot_{};
  std::array<int, 8> permutation_{};
  std::array<int, 8> row_of_{};
  double largest_ = 0.0, smallest_ = 0.0;
  double pivot_ratio_ = 0.0;
};

/// StewartSystem::path_taylor on lanes: taylor[0] given, taylor[1..Order] filled in, `lu` a factorisation of
/// the Jacobian at (or near) taylor[0].
template <int Order>
void path_taylor(const Legs& p, const Legs& rate, const LaneLu& lu, Vec8* taylor) {
  // u = 2g + M e per leg pair and component, by order; at order k only M' e_{k−1} of u_k is known.
  CLane u[Order + 1][4][3];
  Complex e[Order][4], g[Order][4];
  for (int k = 1; k <= Order; ++k) {
    for (int c = 0; c < 4; ++c) {
      e[k - 1][c] = taylor[k - 1].get(c);
      g[k - 1][c] = taylor[k - 1].get(4 + c);
    }
    const Complex* last = e[k - 1];
    for (int q = 0; q < 3; ++q) {
      CLane fixed[4], moved[4];
      leg_products(p, q, last, fixed);
      leg_products(rate, q, last, moved);
      for (int c = 0; c < 4; ++c) {
        const CLane twice_g = broadcast(2.0 * g[k - 1][c]);
        u[k - 1][c][q] = (k == 1 ? fixed[c] : u[k - 1][c][q] + fixed[c]) + twice_g;
        u[k][c][q] = moved[c];
      }
    }
    Complex ee = 0.0, eg = 0.0, ee_below = 0.0;
    for (int i = 1; i < k; ++i) {
      ee += dot4(e[i], e[k - i]);
      eg += dot4(e[i], g[k - i]);
    }
    for (int i = 0; i < k; ++i) ee_below += dot4(e[i], e[k - 1 - i]);
    Vec8 r;
    for (int q = 0; q < 3; ++q) {
      CLane uu{};
      for (int i = 0; 2 * i < k; ++i) {
        for (int c = 0; c < 4; ++c) uu = uu + u[i][c][q] * u[k - i][c][q];
      }
      uu = 2.0 * uu;
      if (k % 2 == 0) {
        for (int c = 0; c < 4; ++c) uu = uu + u[k / 2][c][q] * u[k / 2][c][q];
      }
      r.pair[q] = uu - p.length_squared[q] * ee - rate.length_squared[q] * ee_below;
    }
    r.pair[3] = CLane{Lane{eg.real(), 0.0}, Lane{eg.imag(), 0.0}};
    taylor[k] = lu.solve(r);
    for (int q = 0; q < 4; ++q) taylor[k].pair[q] = CLane{} - taylor[k].pair[q];
  }
}

}  // namespace pkm::stewart_lanes
