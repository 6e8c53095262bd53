#include "kinematics/stewart_system.hpp"

#include "kinematics/complex_lu.hpp"

namespace pkm {

StewartParameters StewartParameters::from_joints(const std::array<Eigen::Vector3cd, 6>& base,
                                                 const std::array<Eigen::Vector3cd, 6>& platform,
                                                 const std::array<Complex, 6>& length_squared) {
  StewartParameters p;
  for (int j = 0; j < 6; ++j) {
    p.d[j] = base[j] - platform[j];
    p.s[j] = base[j] + platform[j];
  }
  p.length_squared = length_squared;
  return p;
}

StewartParameters StewartParameters::minus(const StewartParameters& other) const {
  StewartParameters p;
  for (int j = 0; j < 6; ++j) {
    p.d[j] = d[j] - other.d[j];
    p.s[j] = s[j] - other.s[j];
    p.length_squared[j] = length_squared[j] - other.length_squared[j];
  }
  return p;
}

StewartParameters StewartParameters::lerp_rate(const StewartParameters& rate, double t) const {
  StewartParameters p;
  for (int j = 0; j < 6; ++j) {
    p.d[j] = d[j] + t * rate.d[j];
    p.s[j] = s[j] + t * rate.s[j];
    p.length_squared[j] = length_squared[j] + t * rate.length_squared[j];
  }
  return p;
}

namespace {
using complex_arithmetic::mul;
// a × b without conjugation (Eigen's cross() conjugates complex results, as its dot() conjugates), with the
// products written out (complex_lu.hpp).
Eigen::Vector3cd bilinear_cross(const Eigen::Vector3cd& a, const Eigen::Vector3cd& b) {
  return {mul(a[1], b[2]) - mul(a[2], b[1]), mul(a[2], b[0]) - mul(a[0], b[2]),
          mul(a[0], b[1]) - mul(a[1], b[0])};
}
template <int N>
Complex bilinear_dot(const Eigen::Matrix<Complex, N, 1>& x, const Eigen::Matrix<Complex, N, 1>& y) {
  Complex sum = 0.0;
  for (int i = 0; i < N; ++i) sum += mul(x[i], y[i]);
  return sum;
}
Eigen::Vector3cd complex_scaled(Complex a, const Eigen::Vector3cd& v) {
  return {mul(a, v[0]), mul(a, v[1]), mul(a, v[2])};
}
}  // namespace

// e·b − A·e for pure quaternions A, b (the bilinear_dot forms written out, no conjugation): scalar part (A −
// b)·e_v, vector part e_0 (b − A) + e_v × (A + b).
Eigen::Vector4cd leg_quaternion(const Eigen::Vector3cd& d, const Eigen::Vector3cd& s,
                                const Eigen::Vector4cd& e) {
  const Eigen::Vector3cd ev = e.tail<3>();
  Eigen::Vector4cd y;
  y[0] = bilinear_dot<3>(d, ev);
  y.tail<3>() = bilinear_cross(ev, s) - complex_scaled(e[0], d);
  return y;
}

void StewartSystem::evaluate(const StewartParameters& p, const StudyPoint& x, StudyPoint& f) const {
  const Eigen::Vector4cd e = x.head<4>();
  const Eigen::Vector4cd g = x.tail<4>();
  const Complex gg = bilinear_dot<4>(g, g);
  const Complex ee = bilinear_dot<4>(e, e);
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector4cd y = leg_quaternion(p.d[j], p.s[j], e);
    f[j] = 4.0 * gg + 4.0 * bilinear_dot<4>(g, y) + bilinear_dot<4>(y, y) - mul(p.length_squared[j], ee);
  }
  f[6] = bilinear_dot<4>(e, g);
  f[7] = bilinear_dot<4>(chart_, e) - 1.0;
}

void StewartSystem::linearise(const StewartParameters& p, const StewartParameters* dp, const StudyPoint& x,
                              StudyPoint* f, StudyJacobian& jx, StudyPoint* ft) const {
  // Everything in one pass over the legs, with the leg quaternion y = M e computed once (hot path).
  const Complex e0 = x[0], e1 = x[1], e2 = x[2], e3 = x[3];
  const Complex g0 = x[4], g1 = x[5], g2 = x[6], g3 = x[7];
  const Complex gg = mul(g0, g0) + mul(g1, g1) + mul(g2, g2) + mul(g3, g3);
  const Complex ee = mul(e0, e0) + mul(e1, e1) + mul(e2, e2) + mul(e3, e3);
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3cd& d = p.d[j];
    const Eigen::Vector3cd& sj = p.s[j];
    // y = (d·e_v, e_v × s − e0 d)
    const Complex y0 = mul(d[0], e1) + mul(d[1], e2) + mul(d[2], e3);
    const Complex y1 = mul(e2, sj[2]) - mul(e3, sj[1]) - mul(e0, d[0]);
    const Complex y2 = mul(e3, sj[0]) - mul(e1, sj[2]) - mul(e0, d[1]);
    const Complex y3 = mul(e1, sj[1]) - mul(e2, sj[0]) - mul(e0, d[2]);
    const Complex gy = mul(g0, y0) + mul(g1, y1) + mul(g2, y2) + mul(g3, y3);
    if (f) {
      const Complex yy = mul(y0, y0) + mul(y1, y1) + mul(y2, y2) + mul(y3, y3);
      (*f)[j] = 4.0 * gg + 4.0 * gy + yy - mul(p.length_squared[j], ee);
    }
    // ∂f/∂g = 8g + 4y;  ∂f/∂e = Mᵀw − 2L² e with w = 4g + 2y, Mᵀw = (−d·w_v, w0 d + s × w_v).
    jx(j, 4) = 8.0 * g0 + 4.0 * y0;
    jx(j, 5) = 8.0 * g1 + 4.0 * y1;
    jx(j, 6) = 8.0 * g2 + 4.0 * y2;
    jx(j, 7) = 8.0 * g3 + 4.0 * y3;
    const Complex w0 = 4.0 * g0 + 2.0 * y0, w1 = 4.0 * g1 + 2.0 * y1, w2 = 4.0 * g2 + 2.0 * y2,
                  w3 = 4.0 * g3 + 2.0 * y3;
    const Complex l2 = 2.0 * p.length_squared[j];
    jx(j, 0) = -(mul(d[0], w1) + mul(d[1], w2) + mul(d[2], w3)) - mul(l2, e0);
    jx(j, 1) = mul(w0, d[0]) + mul(sj[1], w3) - mul(sj[2], w2) - mul(l2, e1);
    jx(j, 2) = mul(w0, d[1]) + mul(sj[2], w1) - mul(sj[0], w3) - mul(l2, e2);
    jx(j, 3) = mul(w0, d[2]) + mul(sj[0], w2) - mul(sj[1], w1) - mul(l2, e3);
    if (ft) {
      // ∂f/∂t = 4 gᵀdy + 2 yᵀdy − dL² eᵀe, dy = dM e (M is linear in d and s).
      const Eigen::Vector3cd& dd = dp->d[j];
      const Eigen::Vector3cd& ds = dp->s[j];
      const Complex z0 = mul(dd[0], e1) + mul(dd[1], e2) + mul(dd[2], e3);
      const Complex z1 = mul(e2, ds[2]) - mul(e3, ds[1]) - mul(e0, dd[0]);
      const Complex z2 = mul(e3, ds[0]) - mul(e1, ds[2]) - mul(e0, dd[1]);
      const Complex z3 = mul(e1, ds[1]) - mul(e2, ds[0]) - mul(e0, dd[2]);
      (*ft)[j] = mul(w0, z0) + mul(w1, z1) + mul(w2, z2) + mul(w3, z3) - mul(dp->length_squared[j], ee);
    }
  }
  if (f) {
    (*f)[6] = mul(e0, g0) + mul(e1, g1) + mul(e2, g2) + mul(e3, g3);
    (*f)[7] = mul(chart_[0], e0) + mul(chart_[1], e1) + mul(chart_[2], e2) + mul(chart_[3], e3) - 1.0;
  }
  if (ft) {
    (*ft)[6] = 0.0;
    (*ft)[7] = 0.0;
  }
  for (int i = 0; i < 4; ++i) {
    jx(6, i) = x[4 + i];
    jx(6, 4 + i) = x[i];
    jx(7, i) = chart_[i];
    jx(7, 4 + i) = 0.0;
  }
}

namespace {
using Quad = std::array<Complex, 4>;

// M e for one leg (see leg_quaternion), on one coefficient of a series.
inline Quad leg_product(const Eigen::Vector3cd& d, const Eigen::Vector3cd& s, const Complex* e) {
  return {mul(d[0], e[1]) + mul(d[1], e[2]) + mul(d[2], e[3]),
          mul(e[2], s[2]) - mul(e[3], s[1]) - mul(e[0], d[0]),
          mul(e[3], s[0]) - mul(e[1], s[2]) - mul(e[0], d[1]),
          mul(e[1], s[1]) - mul(e[2], s[0]) - mul(e[0], d[2])};
}
inline Complex dot4(const Complex* a, const Complex* b) {
  return mul(a[0], b[0]) + mul(a[1], b[1]) + mul(a[2], b[2]) + mul(a[3], b[3]);
}
inline Complex dot4(const Quad& a, const Quad& b) {
  return dot4(a.data(), b.data());
}

// path_taylor for a fixed order (the loops unrolled). With u = 2g + y, the leg equation is uᵀu − L² eᵀe.
template <int Order>
void path_taylor_of_order(const StewartParameters& p, const StewartParameters& dp, const ComplexLu<8>& lu,
                          StudyPoint* taylor) {
  // u_i = 2 g_i + M e_i + M' e_{i−1} per leg and known order i; at order k (u_k without its x_k part) only
  // M' e_{k−1} is left.
  std::array<std::array<Quad, Order + 1>, 6> u;
  for (int k = 1; k <= Order; ++k) {
    const StudyPoint& last = taylor[k - 1];  // the newest known coefficient
    for (int j = 0; j < 6; ++j) {
      const Quad moved = leg_product(dp.d[j], dp.s[j], last.data());
      if (k == 1) {
        u[j][0] = leg_product(p.d[j], p.s[j], last.data());
      } else {
        const Quad fixed = leg_product(p.d[j], p.s[j], last.data());
        for (int c = 0; c < 4; ++c) u[j][k - 1][c] += fixed[c];
      }
      for (int c = 0; c < 4; ++c) u[j][k - 1][c] += 2.0 * last[4 + c];
      u[j][k] = moved;
    }
    // eᵀe and eᵀg at order k (x_k = 0), eᵀe at order k − 1.
    Complex ee = 0.0, eg = 0.0, ee_below = 0.0;
    for (int i = 1; i < k; ++i) {
      ee += dot4(taylor[i].data(), taylor[k - i].data());
      eg += dot4(taylor[i].data(), taylor[k - i].data() + 4);
    }
    for (int i = 0; i < k; ++i) ee_below += dot4(taylor[i].data(), taylor[k - 1 - i].data());
    StudyPoint r;
    for (int j = 0; j < 6; ++j) {
      // uᵀu at order k: the symmetric pairs once, doubled.
      Complex uu = 0.0;
      for (int i = 0; 2 * i < k; ++i) uu += dot4(u[j][i], u[j][k - i]);
      uu *= 2.0;
      if (k % 2 == 0) uu += dot4(u[j][k / 2], u[j][k / 2]);
      r[j] = uu - mul(p.length_squared[j], ee) - mul(dp.length_squared[j], ee_below);
    }
    r[6] = eg;
    r[7] = 0.0;  // the chart is linear in x and does not move
    taylor[k] = -lu.solve(r);
  }
}
}  // namespace

void StewartSystem::path_taylor(const StewartParameters& p, const StewartParameters& dp,
                                const ComplexLu<8>& lu, int order, StudyPoint* taylor) const {
  // Series arithmetic on x(s) = Σ x_i s^i with the unknown x_k taken as zero: the coefficient of s^k of each
  // product is then r_k (the J·x_k part is what is left out). The parameters are linear in s: M(s) = M + s·M'
  // and L²(s) = L² + s·dL², so y(s) = M(s) e(s) has y_i = M e_i + M' e_{i−1}. The series of u = 2g + y is
  // kept per leg, so that each order adds one pair of leg products per leg. Order 1 is the velocity
  // −J⁻¹·∂f/∂t.
  switch (order) {
    case 1:
      return path_taylor_of_order<1>(p, dp, lu, taylor);
    case 2:
      return path_taylor_of_order<2>(p, dp, lu, taylor);
    case 3:
      return path_taylor_of_order<3>(p, dp, lu, taylor);
    case 4:
      return path_taylor_of_order<4>(p, dp, lu, taylor);
    default:
      return path_taylor_of_order<5>(p, dp, lu, taylor);
  }
}

std::array<Complex, 6> StewartSystem::lengths_through(const StewartParameters& p, const StudyPoint& x) const {
  const Eigen::Vector4cd e = x.head<4>();
  const Eigen::Vector4cd g = x.tail<4>();
  const Complex gg = bilinear_dot<4>(g, g);
  const Complex ee = bilinear_dot<4>(e, e);
  std::array<Complex, 6> out;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector4cd y = leg_quaternion(p.d[j], p.s[j], e);
    out[j] = (4.0 * gg + 4.0 * bilinear_dot<4>(g, y) + bilinear_dot<4>(y, y)) / ee;
  }
  return out;
}

}  // namespace pkm
