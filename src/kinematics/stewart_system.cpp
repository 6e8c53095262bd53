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
