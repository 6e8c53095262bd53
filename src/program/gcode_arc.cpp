#include "program/gcode_arc.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pkm::program::gcode {

namespace {

// Below this a radius or a chord is taken as zero (far below any tolerance a program can state).
constexpr double kTiny = 1e-9;

Eigen::Vector2d in_plane(const Eigen::Vector3d& p, const PlaneAxes& axes) {
  return {p[axes.first], p[axes.second]};
}

}  // namespace

PlaneAxes axes_of(Plane plane) {
  switch (plane) {
    case Plane::xy:
      return {0, 1, 2};
    case Plane::zx:
      return {2, 0, 1};
    case Plane::yz:
      return {1, 2, 0};
  }
  return {0, 1, 2};
}

Eigen::Vector3d plane_normal(Plane plane) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axes_of(plane).normal] = 1.0;
  return n;
}

ArcTolerances arc_tolerances(bool inch) {
  ArcTolerances t{};
  // rs274 scales this one by ten, not by 25.4, between its inch and mm values.
  t.radius_abs_mm = inch ? 0.002 * std::numbers::sqrt2 * 25.4 : 0.02 * std::numbers::sqrt2;
  return t;
}

ArcProblem check_centre_arc(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                            const Eigen::Vector3d& centre, Plane plane, const ArcTolerances& tolerances) {
  const PlaneAxes axes = axes_of(plane);
  const Eigen::Vector2d c = in_plane(centre, axes);
  const double r_start = (in_plane(start, axes) - c).norm();
  const double r_end = (in_plane(end, axes) - c).norm();
  if (r_start < kTiny) return {"zero-radius arc: the centre is the start point"};
  if (r_end < kTiny) return {"zero-radius arc: the centre is the end point"};
  const double difference = std::abs(r_end - r_start);
  if (difference > tolerances.radius_abs_mm && difference > tolerances.radius_rel * std::max(r_start, r_end))
    return {fmt::format("arc end is not on the circle: radius {:.4f} mm at the start, {:.4f} mm at the end",
                        r_start, r_end)};
  return {};
}

ArcProblem centre_from_radius(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius_mm,
                              bool clockwise, Plane plane, const ArcTolerances& tolerances,
                              Eigen::Vector3d& centre) {
  const PlaneAxes axes = axes_of(plane);
  const Eigen::Vector2d s = in_plane(start, axes);
  const Eigen::Vector2d e = in_plane(end, axes);
  const Eigen::Vector2d chord = e - s;
  const double length = chord.norm();
  if (length < kTiny) return {"R arc with its end point at the start point (use I J K for a full circle)"};
  const double half = 0.5 * length;
  const double r = std::abs(radius_mm);
  if (half - r > tolerances.r_word_mm)
    return {
        fmt::format("arc radius R{:.4f} mm too small to reach the end point ({:.4f} mm away)", r, length)};
  const double offset = r > half ? std::sqrt(r * r - half * half) : 0.0;
  // The centre of the shorter arc lies left of the chord for a counter-clockwise (G3) move; R < 0 asks for
  // the longer arc, whose centre is on the other side.
  const Eigen::Vector2d left(-chord.y() / length, chord.x() / length);
  const double side = (clockwise ? -1.0 : 1.0) * (radius_mm < 0.0 ? -1.0 : 1.0);
  const Eigen::Vector2d c = 0.5 * (s + e) + side * offset * left;
  centre = start;
  centre[axes.first] = c.x();
  centre[axes.second] = c.y();
  return {};
}

double arc_sweep_rad(const Eigen::Vector3d& start, const CanonicalMove& arc) {
  const PlaneAxes axes = axes_of(arc.plane);
  const Eigen::Vector2d c = in_plane(arc.center_mm, axes);
  const Eigen::Vector2d s = in_plane(start, axes) - c;
  const Eigen::Vector2d e = in_plane(arc.end_mm, axes) - c;
  const double a0 = std::atan2(s.y(), s.x());
  const double a1 = std::atan2(e.y(), e.x());
  const bool counter_clockwise = arc.normal.dot(plane_normal(arc.plane)) > 0.0;
  double sweep = counter_clockwise ? a1 - a0 : a0 - a1;
  // As LinuxCNC: an end at (or behind) the start angle goes round; the same angle is a full circle.
  if (sweep <= 0.0) sweep += 2.0 * std::numbers::pi;
  return sweep + 2.0 * std::numbers::pi * (arc.turns - 1);
}

double arc_length_mm(const Eigen::Vector3d& start, const CanonicalMove& arc) {
  const PlaneAxes axes = axes_of(arc.plane);
  const double radius = (in_plane(start, axes) - in_plane(arc.center_mm, axes)).norm();
  const double along = arc.end_mm[axes.normal] - start[axes.normal];
  return std::hypot(radius * arc_sweep_rad(start, arc), along);
}

}  // namespace pkm::program::gcode
