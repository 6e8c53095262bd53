#include "path/curve.hpp"

#include <algorithm>
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

Eigen::Vector3d Curve::tip_velocity(double f) const {
  if (kind == CurveKind::line) return end_mm - start_mm;
  const double angle = std::clamp(f, 0.0, 1.0) * sweep_rad;
  const double radius = radius_mm + std::clamp(f, 0.0, 1.0) * (radius_end_mm - radius_mm);
  const Eigen::Vector3d radial = std::cos(angle) * u + std::sin(angle) * v;
  const Eigen::Vector3d across = -std::sin(angle) * u + std::cos(angle) * v;
  return (radius_end_mm - radius_mm) * radial + (radius * sweep_rad) * across + axial_mm * normal;
}

Eigen::Vector3d Curve::angular_rate() const {
  if (rotation_angle_rad == 0.0) return Eigen::Vector3d::Zero();
  // Slerp turns at a constant rate about one fixed axis: R(f) = R0·exp(f·θ·k), so ω = θ·(R0·k) in the base
  // frame.
  Eigen::Quaterniond delta = start_rotation.conjugate() * end_rotation;
  if (delta.w() < 0.0) delta.coeffs() = -delta.coeffs();  // the short way, as slerp_short takes it
  const Eigen::AngleAxisd turn(delta);
  return turn.angle() * (start_rotation * turn.axis());
}

Eigen::Vector3d Curve::velocity(double f) const {
  if (tool_length_mm == 0.0 || rotation_angle_rad == 0.0) return tip_velocity(f);
  // The tool axis turns with the platform: d/df (R(f)·a) = ω × (R(f)·a).
  return tip_velocity(f) + tool_length_mm * angular_rate().cross(rotation(f) * tool_axis_platform);
}

Eigen::Quaterniond Curve::rotation(double f) const {
  return slerp_short(start_rotation, end_rotation, f);
}

}  // namespace pkm::path
