#pragma once
// The path tracker's arithmetic (kinematics/stewart_homotopy.cpp) on pairs of doubles: the same equations,
// Jacobian and Taylor coefficients as StewartSystem, and an LU like ComplexLu<8>'s but pivoting by columns
// (those stay the reference the tests compare with), laid out so that every operation works on two complex
// numbers at once.
//
// Why: the tracker spends all its time in complex multiply–adds on 8×8 and 6-leg data. Written one complex
// number at a time they run at the scalar floating-point rate (one double per instruction); with the real and
// the imaginary parts in separate two-lane vectors (two legs, two rows of a column), each instruction does
// two, on the baseline x86-64 (SSE2) and AArch64 (NEON) alike, without -march flags. The layout:
// - legs in pairs: leg quantities are vectors over legs (2q, 2q + 1), q = 0, 1, 2;
// - an 8-vector (equations: legs 0–5, Study quadric, chart; unknowns: e0..e3, g0..g3) is 4 pairs;
// - the Jacobian is stored by columns, each column 4 pairs of rows, so that the LU's row operations and the
//   leg equations both fill and update whole pairs;
// - the loops over rows, columns and Taylor orders are unrolled at compile time (static_for), so that no lane
//   is addressed by a run-time index except where a pivot choice decides it.
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
/// acc + a·b and acc − a·b, added term by term so that each part is two fused multiply–adds where the
/// processor has them (a·b formed first and then added would take a multiply, a fused one and an add).
inline CLane mul_add(CLane acc, CLane a, CLane b) {
  return {acc.re + a.re * b.re - a.im * b.im, acc.im + a.re * b.im + a.im * b.re};
}
inline CLane mul_sub(CLane acc, CLane a, CLane b) {
  return {acc.re - a.re * b.re + a.im * b.im, acc.im - a.re * b.im - a.im * b.re};
}

/// |a|² per lane.
inline Lane abs2(CLane a) {
  return a.re * a.re + a.im * a.im;
}
/// a / b per lane (inf or NaN where b = 0).
inline CLane quotient(CLane a, CLane b) {
  const Lane n = abs2(b);
  return {(a.re * b.re + a.im * b.im) / n, (a.im * b.re - a.re * b.im) / n};
}
/// The mask of a comparison of two Lanes: all bits set where true.
using LaneMask = long long __attribute__((vector_size(16)));
/// a where `mask`, b elsewhere.
inline CLane select(LaneMask mask, CLane a, CLane b) {
  return {mask ? a.re : b.re, mask ? a.im : b.im};
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

/// The leg quaternions y = M e of one pair of legs (leg_quaternion), e given in both lanes.
inline void leg_products(const Legs& p, int q, const CLane* e, CLane* y) {
  y[0] = mul_add(mul_add(p.d[0][q] * e[1], p.d[1][q], e[2]), p.d[2][q], e[3]);
  y[1] = mul_sub(mul_sub(p.s[2][q] * e[2], p.s[1][q], e[3]), p.d[0][q], e[0]);
  y[2] = mul_sub(mul_sub(p.s[0][q] * e[3], p.s[2][q], e[1]), p.d[1][q], e[0]);
  y[3] = mul_sub(mul_sub(p.s[1][q] * e[1], p.s[0][q], e[2]), p.d[2][q], e[0]);
}

inline Complex dot4(const Complex* a, const Complex* b) {
  using complex_arithmetic::mul;
  return mul(a[0], b[0]) + mul(a[1], b[1]) + mul(a[2], b[2]) + mul(a[3], b[3]);
}

/// Where the columns of a Jacobian go: column c at column[c] (a Mat8's own order, or the order a LaneLu
/// factorised the last one in: LaneLu::columns_in_last_order).
struct Columns {
  CLane* column[8];
};

/// The equations' values (when f is not null) and Jacobian at x, as StewartSystem::linearise, the Jacobian's
/// columns written where `jx` says.
inline void linearise(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f,
                      const Columns& jx) {
  Complex e[4], g[4];
  CLane e_lanes[4], g_lanes[4];
  for (int c = 0; c < 4; ++c) {
    e[c] = x.get(c);
    g[c] = x.get(4 + c);
    e_lanes[c] = broadcast(e[c]);
    g_lanes[c] = broadcast(g[c]);
  }
  const CLane four_gg = broadcast(4.0 * dot4(g, g)), ee = broadcast(dot4(e, e));
  for (int q = 0; q < 3; ++q) {
    CLane y[4];
    leg_products(p, q, e_lanes, y);
    if (f) {
      // 4 gᵀg + 4 gᵀy + yᵀy − L² eᵀe, as 4 gᵀg − L² eᵀe + yᵀ(4g + y).
      CLane sum = mul_sub(four_gg, p.length_squared[q], ee);
      for (int c = 0; c < 4; ++c) sum = mul_add(sum, y[c], 4.0 * g_lanes[c] + y[c]);
      f->pair[q] = sum;
    }
    // ∂f/∂g = 8g + 4y;  ∂f/∂e = Mᵀw − 2L² e with w = 4g + 2y, Mᵀw = (−d·w_v, w0 d + s × w_v).
    CLane w[4];
    for (int c = 0; c < 4; ++c) {
      w[c] = 4.0 * g_lanes[c] + 2.0 * y[c];
      jx.column[4 + c][q] = 2.0 * w[c];
    }
    const CLane l2 = 2.0 * p.length_squared[q];
    jx.column[0][q] = CLane{} - mul_add(mul_add(mul_add(l2 * e_lanes[0], p.d[0][q], w[1]), p.d[1][q], w[2]),
                                        p.d[2][q], w[3]);
    jx.column[1][q] =
        mul_sub(mul_sub(mul_add(w[0] * p.d[0][q], p.s[1][q], w[3]), p.s[2][q], w[2]), l2, e_lanes[1]);
    jx.column[2][q] =
        mul_sub(mul_sub(mul_add(w[0] * p.d[1][q], p.s[2][q], w[1]), p.s[0][q], w[3]), l2, e_lanes[2]);
    jx.column[3][q] =
        mul_sub(mul_sub(mul_add(w[0] * p.d[2][q], p.s[0][q], w[2]), p.s[1][q], w[1]), l2, e_lanes[3]);
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

/// The same with the Jacobian into a Mat8, in its own column order.
inline void linearise(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f, Mat8& jx) {
  Columns columns;
  for (int c = 0; c < 8; ++c) columns.column[c] = jx.column[c];
  linearise(p, chart, x, f, columns);
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

/// LU with partial pivoting of a Mat8 by columns, as ComplexLu<8> does it by rows: A·P = L·U, P the column
/// interchanges. The Mat8 is stored by columns, so that choosing the pivot among the columns of row K reads
/// one fixed lane of each, and an interchange swaps two whole columns; row interchanges would move single
/// lanes of every column to places known only at run time (they took half of the factorisation's
/// instructions). The factors overwrite the matrix: after step K, column K holds the multipliers of L below
/// the diagonal, with a zero on the diagonal when it shares a pair with them (K even), so that the updates
/// and the forward solve leave row K alone. U is kept as D·U′, D its diagonal (the pivots, kept apart,
/// inverted) and U′ unit upper triangular, stored above the diagonal with a zero on it where it shares a pair
/// with the rows above (K odd): the back substitution then multiplies by no pivot in its chain of dependent
/// steps.
///
/// factorise_in_last_order: a path tracker factorises a Jacobian that changed little since the last one, in
/// whose column order partial pivoting would almost always choose the diagonal again. Written in that order
/// (columns_in_last_order), it is factorised without the pivot search and interchanges (a tenth of the
/// tracker's time), and the order is kept where it still bounds every |U′_Kj| by kReuseBound, the threshold
/// pivoting of sparse solvers (MA48, UMFPACK: a pivot at least 0.1 of the largest in its row); otherwise the
/// caller factorises with the search.
class LaneLu {
 public:
  /// |U′_Kj| = |U_Kj / U_KK| allowed in the last order (partial pivoting keeps it at most 1).
  static constexpr double kReuseBound = 10.0;

  bool compute(const Mat8& m) {
    a_ = m;
    return factorise();
  }

  /// The matrix to factorise, to be filled in place (the tracker's linearise writes the Jacobian here).
  Mat8& matrix() { return a_; }

  /// Where to write the matrix, column c at the position the last factorisation moved column c to, for
  /// factorise_in_last_order. Before any factorisation: the matrix's own order.
  Columns columns_in_last_order() {
    Columns columns;
    for (int c = 0; c < 8; ++c) columns.column[c] = a_.column[position_[c]];
    return columns;
  }

  /// Factorises matrix(), filled in its own column order, in place, choosing the pivots.
  [[gnu::always_inline]] bool factorise() {
    for (int k = 0; k < 8; ++k) order_[k] = k;
    if (!run<true>()) return false;
    for (int k = 0; k < 8; ++k) position_[order_[k]] = k;
    return true;
  }

  /// Factorises the matrix written through columns_in_last_order in place, with the pivots on its diagonal;
  /// false, the matrix spent, where a pivot is zero or some |U′_Kj| exceeds kReuseBound.
  [[gnu::always_inline]] bool factorise_in_last_order() { return run<false>(); }

  Vec8 solve(const Vec8& b) const {
    Vec8 y = b;
    // L y = b: column k's rows below k (the pair of row k, k even, has the zero in row k's lane).
    static_for<0, 7>([&](auto k) __attribute__((always_inline)) {
      const CLane yk = broadcast(y.get(k));
      for (int q = (k + 1) / 2; q < 4; ++q) y.pair[q] = mul_sub(y.pair[q], a_.column[k][q], yk);
    });
    // U′ z = D⁻¹ y from the last row up, with column k's rows above k (for k odd their last pair also holds
    // row k, whose zero leaves z_k alone).
    for (int q = 0; q < 4; ++q) y.pair[q] = y.pair[q] * inverse_pivots_[q];
    static_for<0, 8>([&](auto kk) __attribute__((always_inline)) {
      constexpr int k = 7 - kk;
      const CLane zk = broadcast(y.get(k));
      for (int q = 0; q < (k + 1) / 2; ++q) y.pair[q] = mul_sub(y.pair[q], a_.column[k][q], zk);
    });
    // x = P·z: unknown order_[k] was at position k.
    Vec8 x;
    static_for<0, 8>([&](auto i) __attribute__((always_inline)) { x.set(i, y.get(position_[i])); });
    return x;
  }

  double pivot_ratio() const { return pivot_ratio_; }

 private:
  template <bool Search>
  [[gnu::always_inline]] bool run() {
    largest_ = 0.0;
    smallest_ = INFINITY;
    bool regular = true;
    static_for<0, 8>([&](auto k) __attribute__((always_inline)) {
      if (regular) regular = eliminate<k, Search>();
    });
    if (!regular) {
      pivot_ratio_ = 0.0;
      return false;
    }
    // U′ = D⁻¹·U, row by row: each pair of each column's part above the diagonal times the pair of inverse
    // pivots of its rows (gathered once here: lanes stored one at a time and then loaded as pairs would stall
    // the store forwarding).
    for (int q = 0; q < 4; ++q) {
      inverse_pivots_[q] = {Lane{inverse_pivot_[2 * q].real(), inverse_pivot_[2 * q + 1].real()},
                            Lane{inverse_pivot_[2 * q].imag(), inverse_pivot_[2 * q + 1].imag()}};
    }
    Lane largest_ratio{};
    static_for<1, 8>([&](auto j) __attribute__((always_inline)) {
      for (int q = 0; q < (j + 1) / 2; ++q) {
        a_.column[j][q] = a_.column[j][q] * inverse_pivots_[q];
        if constexpr (!Search) {
          const Lane ratio = abs2(a_.column[j][q]);
          largest_ratio = ratio > largest_ratio ? ratio : largest_ratio;
        }
      }
      if constexpr (j % 2 == 1) {
        // The unit diagonal of row j, lane 1 of a pair with row j − 1 above it: zero, as a shuffle.
        CLane& pair = a_.column[j][j / 2];
        pair = {__builtin_shufflevector(pair.re, Lane{}, 0, 2),
                __builtin_shufflevector(pair.im, Lane{}, 0, 2)};
      }
    });
    pivot_ratio_ = std::sqrt(smallest_ / largest_);
    if constexpr (!Search) {
      constexpr double bound = kReuseBound * kReuseBound;
      return std::max(largest_ratio[0], largest_ratio[1]) <= bound;
    }
    return true;
  }

  template <int K, bool Search>
  [[gnu::always_inline]] bool eliminate() {
    constexpr int q = K / 2, lane = K % 2;
    double best = lane_abs2(a_.column[K][q], lane);
    if constexpr (Search) {
      int pivot = K;
      static_for<K + 1, 8>([&](auto j) __attribute__((always_inline)) {
        const double v = lane_abs2(a_.column[j][q], lane);
        if (v > best) {
          best = v;
          pivot = j;
        }
      });
      if (pivot != K) {
        for (int r = 0; r < 4; ++r) std::swap(a_.column[K][r], a_.column[pivot][r]);
        std::swap(order_[K], order_[pivot]);
      }
    }
    largest_ = std::max(largest_, best);
    smallest_ = std::min(smallest_, best);
    if (best == 0.0) return false;
    const Complex pivot_value = {a_.column[K][q].re[lane], a_.column[K][q].im[lane]};
    const Complex inverse = {pivot_value.real() / best, -pivot_value.imag() / best};
    inverse_pivot_[K] = inverse;
    // The multipliers of the rows below K, from the pair holding row K + 1 on.
    constexpr int q0 = (K + 1) / 2;
    const CLane inverse_lanes = broadcast(inverse);
    for (int r = q0; r < 4; ++r) a_.column[K][r] = a_.column[K][r] * inverse_lanes;
    if constexpr (K % 2 == 0) {
      // Lane 0 (row K) zero, as a shuffle: a store of one lane followed by loads of the whole pair would
      // stall the store forwarding.
      CLane& pair = a_.column[K][q0];
      pair = {__builtin_shufflevector(pair.re, Lane{}, 2, 1), __builtin_shufflevector(pair.im, Lane{}, 2, 1)};
    }
    static_for<K + 1, 8>([&](auto j) __attribute__((always_inline)) {
      const CLane b = broadcast({a_.column[j][q].re[lane], a_.column[j][q].im[lane]});
      for (int r = q0; r < 4; ++r) a_.column[j][r] = mul_sub(a_.column[j][r], a_.column[K][r], b);
    });
    return true;
  }

  [[gnu::always_inline]] static double lane_abs2(const CLane& pair, int lane) {
    const double re = pair.re[lane], im = pair.im[lane];
    return re * re + im * im;
  }

  Mat8 a_;
  std::array<Complex, 8> inverse_pivot_{};
  /// The same by pairs of rows (D⁻¹).
  CLane inverse_pivots_[4] = {};
  /// order_[k]: the column of the matrix at position k of the factors (A·P's column k); position_ its
  /// inverse. The matrix's own order until the first factorisation.
  std::array<int, 8> order_ = {0, 1, 2, 3, 4, 5, 6, 7};
  std::array<int, 8> position_ = {0, 1, 2, 3, 4, 5, 6, 7};
  double largest_ = 0.0, smallest_ = 0.0;
  double pivot_ratio_ = 0.0;
};

/// StewartSystem::path_taylor on lanes: taylor[0] given, taylor[1..Order] filled in, `lu` a factorisation of
/// the Jacobian at (or near) taylor[0]. The orders are unrolled, so that every index is a constant.
template <int Order>
void path_taylor(const Legs& p, const Legs& rate, const LaneLu& lu, Vec8* taylor) {
  // u = 2g + M e per leg pair and component, by order; at order k only M' e_{k−1} of u_k is known.
  CLane u[Order + 1][4][3];
  static_for<1, Order + 1>([&](auto order) __attribute__((always_inline)) {
    constexpr int k = order;
    const Vec8& last = taylor[k - 1];
    CLane e[4], twice_g[4];
    for (int c = 0; c < 4; ++c) {
      e[c] = broadcast(last.get(c));
      twice_g[c] = broadcast(2.0 * last.get(4 + c));
    }
    for (int q = 0; q < 3; ++q) {
      CLane fixed[4], moved[4];
      leg_products(p, q, e, fixed);
      leg_products(rate, q, e, moved);
      for (int c = 0; c < 4; ++c) {
        u[k - 1][c][q] = (k == 1 ? fixed[c] : u[k - 1][c][q] + fixed[c]) + twice_g[c];
        u[k][c][q] = moved[c];
      }
    }
    // eᵀe and eᵀg at order k (x_k = 0), eᵀe at order k − 1: e is pairs 0 and 1 of a Vec8, g pairs 2 and 3.
    CLane ee{}, eg{}, ee_below{};
    for (int i = 1; i < k; ++i) {
      const Vec8 &a = taylor[i], &b = taylor[k - i];
      ee = mul_add(mul_add(ee, a.pair[0], b.pair[0]), a.pair[1], b.pair[1]);
      eg = mul_add(mul_add(eg, a.pair[0], b.pair[2]), a.pair[1], b.pair[3]);
    }
    for (int i = 0; i < k; ++i) {
      const Vec8 &a = taylor[i], &b = taylor[k - 1 - i];
      ee_below = mul_add(mul_add(ee_below, a.pair[0], b.pair[0]), a.pair[1], b.pair[1]);
    }
    const CLane ee_sum = broadcast({ee.re[0] + ee.re[1], ee.im[0] + ee.im[1]});
    const CLane ee_below_sum = broadcast({ee_below.re[0] + ee_below.re[1], ee_below.im[0] + ee_below.im[1]});
    // The residual with its sign turned, so that the solve gives x_k = −J⁻¹ r_k at once.
    Vec8 minus_r;
    for (int q = 0; q < 3; ++q) {
      // One sum per component, added at the end: four short chains of dependent multiply–adds instead of
      // one long one.
      CLane uu[4] = {};
      for (int i = 0; 2 * i < k; ++i) {
        for (int c = 0; c < 4; ++c) uu[c] = mul_add(uu[c], u[i][c][q], u[k - i][c][q]);
      }
      for (int c = 0; c < 4; ++c) uu[c] = 2.0 * uu[c];
      if constexpr (k % 2 == 0) {
        for (int c = 0; c < 4; ++c) uu[c] = mul_add(uu[c], u[k / 2][c][q], u[k / 2][c][q]);
      }
      minus_r.pair[q] = p.length_squared[q] * ee_sum + rate.length_squared[q] * ee_below_sum -
                        ((uu[0] + uu[1]) + (uu[2] + uu[3]));
    }
    minus_r.pair[3] = CLane{Lane{-(eg.re[0] + eg.re[1]), 0.0}, Lane{-(eg.im[0] + eg.im[1]), 0.0}};
    taylor[k] = lu.solve(minus_r);
  });
}

}  // namespace pkm::stewart_lanes
