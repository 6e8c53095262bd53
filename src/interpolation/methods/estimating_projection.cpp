#include "interpolation/methods/estimating_projection.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::interpolation {

namespace {
/// Central-difference step of the path derivative (path units): the path is smooth within a segment and C¹
/// across blends; 1e-4 keeps both the truncation (h²·P'''/6) and the round-off (1e-13 mm / h) below 1e-9.
constexpr double kEstimatingDerivativeStep = 1e-4;
/// Newton on the path parameter stops when a step is below this (mm of path).
constexpr double kEstimatingParameterTolerance = 1e-10;
constexpr int kEstimatingNewtonSteps = 12;
constexpr double kEstimatingPi = 3.14159265358979323846;
}  // namespace

EstimatingProjector::EstimatingProjector(const path::Path& path, const AxisMask& axes)
    : path_(path), length_(path.length()) {
  for (int c = 0; c < 3; ++c) controlled_[c] = axes.controlled[c];
  end_mm_ = mask(path.end_point().position_mm);
  anchor(0.0);
}

EstimatingProjector::Local EstimatingProjector::local(double s, int& hint) const {
  Local out;
  const path::PathPoint at = path_.evaluate(s, hint);
  out.point = mask(at.position_mm);
  out.rotation = at.rotation;
  const double a = std::max(0.0, s - kEstimatingDerivativeStep);
  const double b = std::min(length_, s + kEstimatingDerivativeStep);
  if (b > a) {
    int hint_a = hint;
    int hint_b = hint;
    out.derivative =
        mask(path_.evaluate(b, hint_b).position_mm - path_.evaluate(a, hint_a).position_mm) / (b - a);
  } else {
    out.derivative.setZero();
  }
  return out;
}

void EstimatingProjector::anchor(double s) {
  anchor_s_ = std::clamp(s, 0.0, length_);
  anchor_ = local(anchor_s_, anchor_hint_);
}

EstimatingNearest EstimatingProjector::nearest(const Eigen::Vector3d& point_mm) const {
  const Eigen::Vector3d p = mask(point_mm);
  // The nearest point is no farther from p than the anchor point is, so it lies within a chord of 2·|p − P0|
  // of the anchor; an arc up to a half turn is at most π/2 times its chord.
  const double window = kEstimatingPi * (p - anchor_.point).norm() + 1e-6;
  const double lo = std::max(0.0, anchor_s_ - window);
  const double hi = std::min(length_, anchor_s_ + window);
  int hint = anchor_hint_;
  double s = anchor_s_;
  Local at = anchor_;
  bool clamped = false;
  for (int step = 0; step < kEstimatingNewtonSteps; ++step) {
    const double speed2 = at.derivative.squaredNorm();
    if (!(speed2 > 1e-18)) break;  // only the orientation moves here (refused by the interpolator's start)
    // Gauss–Newton on |P(s) − p|²/2: converges at the rate deviation × curvature, i.e. at once on lines
    // and within a few steps on arcs and blends for points micrometres off the path.
    const double wanted = s + (p - at.point).dot(at.derivative) / speed2;
    const double next = std::clamp(wanted, lo, hi);
    clamped = next != wanted;
    if (std::abs(next - s) <= kEstimatingParameterTolerance) break;
    s = next;
    at = local(s, hint);
  }
  EstimatingNearest out;
  out.s = s;
  out.rotation = at.rotation;
  const Eigen::Vector3d r = p - at.point;
  const double speed2 = at.derivative.squaredNorm();
  // Converged inside: the perpendicular part (exact to second order in the last tiny step). At a path end or
  // the window's edge the nearest point is that end itself.
  out.distance_mm =
      clamped || !(speed2 > 1e-18) ? r.norm() : (r - r.dot(at.derivative) / speed2 * at.derivative).norm();
  return out;
}

double EstimatingProjector::distance_to_end_mm(const Eigen::Vector3d& point_mm) const {
  return (mask(point_mm) - end_mm_).norm();
}

int EstimatingProjector::line_at(double s) const {
  if (path_.segments.empty()) return 0;
  // From the last segment find_segment binary-searches backwards: O(log n) for any s.
  return path_.segments[path_.find_segment(s, static_cast<int>(path_.segments.size()) - 1)].line;
}

}  // namespace pkm::interpolation
