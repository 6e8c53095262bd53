#include "kinematics/trilateration.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace pkm {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// A squared height within rounding of zero (the quadratic's discriminant is a difference of squares of size
// `scale_sq`) counts as a tangent contact: its square root would only amplify the rounding.
double squared_rounding_floor(double scale_sq, double tolerance_mm) {
  return std::fmax(tolerance_mm * tolerance_mm, 16.0 * kEpsilon * scale_sq);
}

}  // namespace

const char* to_string(TrilaterationStatus status) {
  switch (status) {
    case TrilaterationStatus::two_points:
      return "two points";
    case TrilaterationStatus::one_point:
      return "one point (the spheres touch)";
    case TrilaterationStatus::infeasible_lengths:
      return "the lengths are infeasible: the spheres do not meet";
    case TrilaterationStatus::collinear_centres:
      return "the three centres are collinear";
    case TrilaterationStatus::centres_not_level:
      return "the centres do not lie in one horizontal plane";
  }
  return "?";
}

SphereIntersection intersect_three_spheres(const std::array<Eigen::Vector3d, 3>& c,
                                           const std::array<double, 3>& r, double touch_tolerance_mm) {
  SphereIntersection out;
  const Eigen::Vector3d u = c[1] - c[0];
  const Eigen::Vector3d v = c[2] - c[0];
  const Eigen::Vector3d n = u.cross(v);
  const double uu = u.squaredNorm(), vv = v.squaredNorm(), uv = u.dot(v);
  // |u × v|² = uu·vv − uv² is the determinant of the 2×2 system below; relative size = sin² of the corner
  // angle.
  const double det = n.squaredNorm();
  if (!(det > 1e-24 * uu * vv) || uu == 0.0 || vv == 0.0) {
    out.status = TrilaterationStatus::collinear_centres;
    return out;
  }
  if (!(r[0] > 0.0 && r[1] > 0.0 && r[2] > 0.0)) return out;  // infeasible_lengths
  out.normal = n / std::sqrt(det);

  // |B−A2|² − |B−A1|² and |B−A3|² − |B−A1|² are linear in B: with B = A1 + αu + βv + h·normal,
  //   u·(B−A1) = (r1² − r2² + |u|²)/2,  v·(B−A1) = (r1² − r3² + |v|²)/2.
  const double ru = 0.5 * (r[0] * r[0] - r[1] * r[1] + uu);
  const double rv = 0.5 * (r[0] * r[0] - r[2] * r[2] + vv);
  const double alpha = (ru * vv - rv * uv) / det;
  const double beta = (rv * uu - ru * uv) / det;
  const Eigen::Vector3d in_plane = alpha * u + beta * v;
  const Eigen::Vector3d foot = c[0] + in_plane;
  // The remaining quadratic, |B − A1|² = r1²: h² = r1² − |αu + βv|².
  const double h_sq = r[0] * r[0] - in_plane.squaredNorm();
  const double floor_sq =
      squared_rounding_floor(std::fmax(r[0] * r[0], in_plane.squaredNorm()), touch_tolerance_mm);
  if (h_sq < -floor_sq) return out;  // infeasible_lengths
  if (h_sq <= floor_sq) {
    out.status = TrilaterationStatus::one_point;
    out.count = 1;
    out.above_mm = out.below_mm = foot;
    return out;
  }
  out.status = TrilaterationStatus::two_points;
  out.count = 2;
  out.height_mm = std::sqrt(h_sq);
  out.above_mm = foot + out.height_mm * out.normal;
  out.below_mm = foot - out.height_mm * out.normal;
  return out;
}

QuaternionTrilateration quaternion_trilateration(const std::array<Eigen::Vector3d, 3>& a,
                                                 const std::array<double, 3>& l, double level_tolerance_mm) {
  QuaternionTrilateration out;
  // The algorithm needs XOY parallel to the joint plane (Smirnov 2019, §2.3.3).
  if (std::abs(a[0].z() - a[1].z()) > level_tolerance_mm ||
      std::abs(a[2].z() - a[1].z()) > level_tolerance_mm) {
    out.status = TrilaterationStatus::centres_not_level;
    return out;
  }
  // (56) coefficients; rod 2 is the reference rod whose quaternion Λ_A2 is solved for.
  out.a11 = a[0].y() - a[1].y();
  out.a12 = a[1].x() - a[0].x();
  out.a21 = a[2].y() - a[1].y();
  out.a22 = a[1].x() - a[2].x();
  const double det = out.a11 * out.a22 - out.a12 * out.a21;
  const double scale_sq = (a[1] - a[0]).squaredNorm() * (a[2] - a[1]).squaredNorm();
  if (!(det * det > 1e-24 * scale_sq) || scale_sq == 0.0) {
    out.status = TrilaterationStatus::collinear_centres;
    return out;
  }
  if (!(l[0] > 0.0 && l[1] > 0.0 && l[2] > 0.0)) return out;  // infeasible_lengths
  const double dx21 = a[1].x() - a[0].x(), dy21 = a[1].y() - a[0].y();
  const double dx23 = a[1].x() - a[2].x(), dy23 = a[1].y() - a[2].y();
  out.b1 = (l[0] * l[0] - l[1] * l[1] - dy21 * dy21 - dx21 * dx21) / (4.0 * l[1]);
  out.b2 = (l[2] * l[2] - l[1] * l[1] - dy23 * dy23 - dx23 * dx23) / (4.0 * l[1]);
  out.lambda01 = (out.b1 * out.a22 - out.a12 * out.b2) / det;
  out.lambda02 = (out.a11 * out.b2 - out.a21 * out.b1) / det;

  // (57): λ0⁴ − λ0² + λ01² + λ02² = 0, from λ1 = λ01/λ0, λ2 = λ02/λ0 and λ0² + λ1² + λ2² = 1.
  const double discriminant = 1.0 - 4.0 * (out.lambda01 * out.lambda01 + out.lambda02 * out.lambda02);
  const double floor = 16.0 * kEpsilon;
  if (discriminant < -floor) return out;  // infeasible_lengths: no real λ0
  const double root = discriminant > floor ? std::sqrt(discriminant) : 0.0;
  out.count = root > 0.0 ? 2 : 1;
  out.status = root > 0.0 ? TrilaterationStatus::two_points : TrilaterationStatus::one_point;

  auto make_root = [&](double lambda0_sq) {
    QuaternionRoot q;
    q.lambda0 = std::sqrt(std::fmax(lambda0_sq, 0.0));
    if (q.lambda0 > 0.0) {
      q.lambda1 = out.lambda01 / q.lambda0;  // (58)
      q.lambda2 = out.lambda02 / q.lambda0;
    } else {
      q.lambda1 = 1.0;  // λ0 = 0 only when λ01 = λ02 = 0: a half turn about x takes the rod straight down
    }
    // (59); x and y use the products λ0λ2 = λ02, λ0λ1 = λ01 directly, and λ0² − λ1² − λ2² = 2λ0² − 1.
    q.point_mm = Eigen::Vector3d(2.0 * out.lambda02 * l[1] + a[1].x(), -2.0 * out.lambda01 * l[1] + a[1].y(),
                                 (2.0 * lambda0_sq - 1.0) * l[1] + a[1].z());
    return q;
  };
  // '+' gives z_B − z_A = +√(1 − 4(λ01² + λ02²))·L2 > 0: B above the joint plane (§2.3.3; sign corrected).
  // The '−' root from Vieta (product of the roots = λ01² + λ02²): 1 − √(1 − 4s) would cancel for small s.
  const double plus_sq = 0.5 * (1.0 + root);
  out.plus = make_root(plus_sq);
  out.minus = make_root((out.lambda01 * out.lambda01 + out.lambda02 * out.lambda02) / plus_sq);
  return out;
}

}  // namespace pkm
