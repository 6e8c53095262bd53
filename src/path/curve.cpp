#include "path/curve.hpp"

#include <cmath>
#include <numbers>

namespace pkm::path {

Eigen::Quaterniond slerp_short(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double w) {
  if (w <= 0.0) return a;
  if (w >= 1.0) return b;
  return a.slerp(w, b);  // Eigen's slerp already takes the shorter arc (it flips b when a·b < 0)
}

static void set_rotations(Curve& c, const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1) {
  c.start_rotation = q0.normalized();
  c.end_rotation = q1.normalized();
  c.rotation_angle_rad = c.start_rotation.angularDistance(c.end_rotation);
}

Curve make_line(const Eigen::Vector3d& start_mm, const Eigen::Vector3d& end_mm, const Eigen::Quaterniond& q0,
                const Eigen::Quaterniond& q1) {
  Curve c;
  c.kind = CurveKind::line;
  c.start_mm = start_mm;
  c.end_mm = end_mm;
  set_rotations(c, q0, q1);
  c.translation_mm = (end_mm - start_mm).norm();
  c.param_length = c.rotation_only() ? c.rotation_angle_rad * 180.0 / std::numbers::pi : c.translation_mm;
  return c;
}

Curve make_helix(const Eigen::Vector3d& start_mm, const Eigen::Vector3d& end_mm,
                 const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal, int turns,
                 const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1) {
  Curve c;
  c.kind = CurveKind::helix;
  c.start_mm = start_mm;
  c.end_mm = end_mm;
  c.normal = normal.normalized();
  // Put the centre in the start's plane, so that p(0) = start exactly.
  c.centre_mm = centre_mm + c.normal * c.normal.dot(start_mm - centre_mm);
  const Eigen::Vector3d radial_start = start_mm - c.centre_mm;
  c.radius_mm = radial_start.norm();
  c.u = radial_start / c.radius_mm;
  c.v = c.normal.cross(c.u);
  const Eigen::Vector3d to_end = end_mm - c.centre_mm;
  c.axial_mm = c.normal.dot(to_end);
  const Eigen::Vector3d radial_end = to_end - c.axial_mm * c.normal;
  c.radius_end_mm = radial_end.norm();
  double angle = std::atan2(radial_end.dot(c.v), radial_end.dot(c.u));  // (-π, π]
  if (angle <= 1e-12) angle += 2.0 * std::numbers::pi;                  // a full circle when start == end
  c.sweep_rad = angle + 2.0 * std::numbers::pi * (turns - 1);
  set_rotations(c, q0, q1);
  const double planar_mm = 0.5 * (c.radius_mm + c.radius_end_mm) * c.sweep_rad;
  c.translation_mm = std::hypot(planar_mm, c.axial_mm);
  c.param_length = c.translation_mm;
  return c;
}

Eigen::Vector3d Curve::tip(double f) const {
  if (f >= 1.0) return end_mm;  // exact end of every move, whatever the rounding of the formula
  if (f <= 0.0) return start_mm;
  if (kind == CurveKind::line) return start_mm + f * (end_mm - start_mm);
  const double angle = f * sweep_rad;
  const double radius = radius_mm + f * (radius_end_mm - radius_mm);
  return centre_mm + radius * (std::cos(angle) * u + std::sin(angle) * v) + (f * axial_mm) * normal;
}

Eigen::Quaterniond Curve::rotation(double f) const {
  return slerp_short(start_rotation, end_rotation, f);
}

}  // namespace pkm::path
