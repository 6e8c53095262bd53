#include "interpolation/contour/contour_gauge.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::interpolation {

namespace {
constexpr double kGaugeDerivativeStep = 1e-4;  // path units; central differences of a smooth curve
constexpr int kGaugeNewtonSteps = 8;
}  // namespace

ContourGauge::ContourGauge(const Machine& machine, const path::Path& path) : path_(path) {
  const AxisMask axes = machine.mechanism->controlled_axes();
  for (int c = 0; c < 3; ++c) controlled_[c] = axes.controlled[c];
  // Orientation is an error only where the mechanism sets all of it (or the planar φ alone).
  controls_orientation_ = axes.controlled[5] && axes.controlled[3] == axes.controlled[4];
}

Eigen::Vector3d ContourGauge::mask(Eigen::Vector3d offset_mm) const noexcept {
  for (int c = 0; c < 3; ++c) {
    if (!controlled_[c]) offset_mm[c] = 0.0;
  }
  return offset_mm;
}

Eigen::Vector3d ContourGauge::tangent(double s, int& hint) const noexcept {
  const double length = path_.length();
  const double a = std::max(0.0, s - kGaugeDerivativeStep);
  const double b = std::min(length, s + kGaugeDerivativeStep);
  if (!(b > a)) return Eigen::Vector3d::Zero();
  int hint_a = hint;
  const Eigen::Vector3d pa = path_.evaluate(a, hint_a).position_mm;
  const Eigen::Vector3d pb = path_.evaluate(b, hint).position_mm;
  const Eigen::Vector3d d = mask(pb - pa);
  const double norm = d.norm();
  return norm > 1e-12 * (b - a) ? Eigen::Vector3d(d / norm) : Eigen::Vector3d::Zero();
}

ContourDeviation ContourGauge::measure(const Pose& pose, double s_guess, int& hint) const noexcept {
  const double length = path_.length();
  double s = std::clamp(s_guess, 0.0, length);
  path::PathPoint point = path_.evaluate(s, hint);
  // Newton on f(s) = |P(s) − p|²/2 with the curve's local tangent; the path is smooth within a segment and
  // continuous in s across segments (blends), so a few steps from a nearby guess converge. Every iterate is
  // a path point, so its distance bounds the contour error from above: the nearest one seen is kept. Where
  // the controlled coordinates of the path are flat (a tripod's z during an XY move), a step taken at the
  // edge of the flat part can run far along the path (6 mm on the tripod example, the circle after a rapid).
  double best_s = s;
  path::PathPoint best_point = point;
  double best_distance2 = mask(pose.position_mm - point.position_mm).squaredNorm();
  int best_hint = hint;
  for (int step = 0; step < kGaugeNewtonSteps; ++step) {
    const double a = std::max(0.0, s - kGaugeDerivativeStep);
    const double b = std::min(length, s + kGaugeDerivativeStep);
    if (!(b > a)) break;
    int hint_a = hint;
    int hint_b = hint;
    const Eigen::Vector3d pa = mask(path_.evaluate(a, hint_a).position_mm);
    const Eigen::Vector3d pb = mask(path_.evaluate(b, hint_b).position_mm);
    const Eigen::Vector3d derivative = (pb - pa) / (b - a);
    const double speed2 = derivative.squaredNorm();
    if (speed2 < 1e-18) break;  // only the orientation moves here: the position is the same for all s
    const double ds = mask(pose.position_mm - point.position_mm).dot(derivative) / speed2;
    const double next = std::clamp(s + ds, 0.0, length);
    if (std::abs(next - s) < 1e-12) break;
    s = next;
    point = path_.evaluate(s, hint);
    const double distance2 = mask(pose.position_mm - point.position_mm).squaredNorm();
    if (distance2 < best_distance2) {
      best_distance2 = distance2, best_s = s, best_point = point, best_hint = hint;
    }
  }
  hint = best_hint;
  ContourDeviation deviation;
  deviation.s = best_s;
  deviation.offset_mm = mask(pose.position_mm - best_point.position_mm);
  deviation.distance_mm = deviation.offset_mm.norm();
  if (controls_orientation_) {
    deviation.rotation_rad = Eigen::Quaterniond(pose.rotation).angularDistance(best_point.rotation);
  }
  return deviation;
}

}  // namespace pkm::interpolation
