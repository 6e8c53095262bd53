#include "program/cl_arc.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pkm::program {
namespace {

// Distance of `p` from the circle's axis line.
double radial_distance(const ClCircle& circle, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - circle.center_mm;
  return (d - circle.axis * circle.axis.dot(d)).norm();
}

}  // namespace

Plane cl_nearest_plane(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.cwiseAbs();
  if (a.z() >= a.x() && a.z() >= a.y()) return Plane::xy;
  return a.y() >= a.x() ? Plane::zx : Plane::yz;
}

namespace {

Eigen::Vector3d radial_part(const CanonicalMove& arc, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - arc.center_mm;
  return d - arc.normal * arc.normal.dot(d);
}

}  // namespace

Eigen::Vector3d cl_arc_start_tangent(const CanonicalMove& arc, const Eigen::Vector3d& start_mm) {
  return arc.normal.cross(radial_part(arc, start_mm)).normalized();
}

Eigen::Vector3d cl_arc_end_tangent(const CanonicalMove& arc) {
  return arc.normal.cross(radial_part(arc, arc.end_mm)).normalized();
}

double cl_arc_sweep_rad(const CanonicalMove& arc, const Eigen::Vector3d& start_mm) {
  const Eigen::Vector3d a = radial_part(arc, start_mm);
  const Eigen::Vector3d b = radial_part(arc, arc.end_mm);
  double angle = std::atan2(arc.normal.dot(a.cross(b)), a.dot(b));
  if (angle <= 1e-9) angle += 2.0 * std::numbers::pi;
  return angle;
}

double cl_arc_radius_tolerance(double radius_mm) {
  return std::max(0.005, 1e-3 * radius_mm);
}

std::string make_cl_arc(const ClCircle& stated, const Eigen::Vector3d& start_mm, CanonicalMove& move) {
  ClCircle circle = stated;
  if (!(circle.radius_mm > 0.0)) {  // no radius written: the start point is on the circle by definition
    circle.radius_mm = radial_distance(circle, start_mm);
    if (!(circle.radius_mm > 1e-6)) return "CIRCLE: the start point is on the circle's axis (radius 0)";
  }
  const double tolerance = cl_arc_radius_tolerance(circle.radius_mm);
  const double start_r = radial_distance(circle, start_mm);
  if (std::abs(start_r - circle.radius_mm) > tolerance) {
    return fmt::format("CIRCLE: the start point is {:.4f} mm from the axis, the radius is {:.4f} mm", start_r,
                       circle.radius_mm);
  }
  const double end_r = radial_distance(circle, move.end_mm);
  if (std::abs(end_r - circle.radius_mm) > tolerance) {
    return fmt::format("CIRCLE: the end point is {:.4f} mm from the axis, the radius is {:.4f} mm", end_r,
                       circle.radius_mm);
  }
  move.kind = MoveKind::arc;
  move.center_mm = circle.center_mm + circle.axis * circle.axis.dot(start_mm - circle.center_mm);
  move.normal = circle.axis;
  move.plane = cl_nearest_plane(circle.axis);
  move.turns = std::max(1, circle.turns);
  return {};
}

}  // namespace pkm::program
