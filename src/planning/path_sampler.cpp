// PathSampler (path_sampling.hpp): inverse kinematics, limits and caps at each planning sample, one sample
// behind the path's growing end.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "machine/joint_limits.hpp"
#include "planning/path_sampling.hpp"

namespace pkm::planning {

namespace {

constexpr double kCurvatureShare = 0.5;  // α: share of the actuator acceleration left for the v²·q'' term

Error at_line(const std::string& source, int line, const Error& error) {
  return Error{error.code, fmt::format("{}:{}: {}", source, line, error.message),
               ErrorLocation{source, line, 0, ""}};
}

Error too_many_samples(const std::string& source, int line, double needed, std::size_t bound) {
  return Error{
      ErrorCode::limit_exceeded,
      fmt::format("{}:{}: the path needs {:.3g} planning samples by the end of this line, over the bound "
                  "of {} (one every sample spacing, 5 deg of an arc and 1 deg of turning); raise "
                  "--max-samples to plan it",
                  source, line, needed, bound),
      ErrorLocation{source, line, 0, ""}};
}

/// Derivatives of a sampled function at the middle of three samples (non-uniform central differences).
struct Derivatives {
  double first = 0.0;
  double second = 0.0;
};
Derivatives differentiate(double s0, double s1, double s2, double f0, double f1, double f2) {
  const double h1 = s1 - s0, h2 = s2 - s1;
  const double d1 = (f1 - f0) / h1, d2 = (f2 - f1) / h2;
  return {(h2 * d1 + h1 * d2) / (h1 + h2), 2.0 * (d2 - d1) / (h1 + h2)};
}

// What the actuators' limits allow at a sample (path units per second, and per second²).
struct ActuatorCaps {
  double speed = std::numeric_limits<double>::infinity();
  double accel = std::numeric_limits<double>::infinity();
};

struct DriveCapLimits {
  double margin = 0.95;
  double speed_max = 0.0;
  double accel_max = 0.0;
  double chord_tolerance_mm = 0.0;
  double period_s = 0.0;
};

/// A sample and its neighbours on the grid: where there is none (the path's ends), or at a stop, the
/// derivatives are one-sided.
struct Neighbours {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;
  bool has_before = false, has_after = false;
  bool one_sided() const { return !has_before || !has_after; }
};

// The caps of the header's formulas from q' and q'' by finite differences over the three samples.
ActuatorCaps actuator_caps(const ActuatorVector& q0, const ActuatorVector& q1, const ActuatorVector& q2,
                           const Neighbours& at, bool stop, const DriveCapLimits& limits) {
  ActuatorCaps caps;
  for (int j = 0; j < q1.size(); ++j) {
    double first = 0.0, second = 0.0;
    if (at.one_sided() || stop) {
      // One-sided slopes; at a stop the larger of the two sides governs the acceleration there.
      if (at.has_before) first = std::abs((q1[j] - q0[j]) / (at.s1 - at.s0));
      if (at.has_after) first = std::max(first, std::abs((q2[j] - q1[j]) / (at.s2 - at.s1)));
    } else {
      const Derivatives d = differentiate(at.s0, at.s1, at.s2, q0[j], q1[j], q2[j]);
      first = std::abs(d.first);
      second = std::abs(d.second);
    }
    if (first > 0.0) {
      caps.speed = std::min(caps.speed, limits.margin * limits.speed_max / first);
      caps.accel = std::min(caps.accel, (1.0 - kCurvatureShare) * limits.margin * limits.accel_max / first);
    }
    if (second > 0.0) {
      caps.speed =
          std::min(caps.speed, std::sqrt(kCurvatureShare * limits.margin * limits.accel_max / second));
      caps.speed =
          std::min(caps.speed, std::sqrt(8.0 * limits.chord_tolerance_mm / second) / limits.period_s);
    }
  }
  return caps;
}

// The tool path's own cap at an inner sample from its curvature (by finite differences of the positions of
// the three samples): the normal acceleration κ·v² ≤ a_path and the chord error between servo periods.
double curvature_cap(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                     const Neighbours& at, double path_accel_mm_s2, const DriveCapLimits& limits) {
  Eigen::Vector3d second;
  for (int c = 0; c < 3; ++c) second[c] = differentiate(at.s0, at.s1, at.s2, p0[c], p1[c], p2[c]).second;
  const double curvature = second.norm();
  if (!(curvature > 1e-12)) return std::numeric_limits<double>::infinity();
  return std::min(std::sqrt(path_accel_mm_s2 / curvature),
                  std::sqrt(8.0 * limits.chord_tolerance_mm / curvature) / limits.period_s);
}

}  // namespace

PathSampler::PathSampler(const Machine& machine, std::string source, const path::Path& path,
                         const SamplingSettings& settings)
    : machine_(machine), source_(std::move(source)), path_(path), settings_(settings) {}

Status PathSampler::add_segments(int end) {
  for (; next_segment_ < end; ++next_segment_) {
    const double room = static_cast<double>(settings_.max_samples) - static_cast<double>(count_);
    const double needed = segment_sample_positions(path_, next_segment_, settings_.spacing, room, fractions_);
    if (needed > room) {
      return too_many_samples(source_, path_.segment(next_segment_).line,
                              static_cast<double>(count_) + needed, settings_.max_samples);
    }
    for (double s : fractions_) {
      if (Status placed = place(s, next_segment_, false); !placed) return placed;
    }
  }
  return ok_status();
}

Status PathSampler::finish() {
  if (path_.segments.empty()) return ok_status();
  if (Status placed = place(path_.length(), path_.segment_end() - 1, true); !placed) return placed;
  hand_on_caps(true);
  return ok_status();
}

int PathSampler::first_needed_segment() const {
  int first = next_segment_ - 1;  // move_pieces looks at the segment before
  for (std::size_t back = 1; back <= std::min<std::size_t>(count_, 3); ++back)
    first = std::min(first, ring_[(count_ - back) % 3].segment);
  return std::max(first, 0);
}

Status PathSampler::place(double s, int segment, bool last) {
  if (count_ > 0 && s <= ring_[(count_ - 1) % 3].s) {
    if (!last) return ok_status();
    // The path's end coincides with the sample placed last (rounding): that one is the last, at rest.
    Point& end = ring_[(count_ - 1) % 3];
    const path::Segment& previous = path_.segment(count_ > 1 ? ring_[(count_ - 2) % 3].segment : end.segment);
    if (count_ > 1 && !end.stop && previous.stop_after)
      end.hold_s += previous.dwell_after_s + settings_.stop_hold_s;
    end.last = end.stop = true;
    end.hold_s = std::max(end.hold_s, settings_.stop_hold_s);
    return ok_status();
  }
  if (count_ >= settings_.max_samples)
    return too_many_samples(source_, path_.segment(segment).line, static_cast<double>(count_ + 1),
                            settings_.max_samples);
  Point& point = ring_[count_ % 3];
  point.s = s;
  point.segment = segment;
  point.last = last;
  // Stops: the end of a segment that must come to rest (corners without blends, dwells, the program end),
  // with the time to hold there.
  if (count_ == 0) {
    point.stop = true;
    point.hold_s = path_.initial_dwell_s;
  } else {
    const path::Segment& previous = path_.segment(ring_[(count_ - 1) % 3].segment);
    const bool boundary = last || ring_[(count_ - 1) % 3].segment != segment;
    point.stop = last || (boundary && previous.stop_after);
    point.hold_s = boundary && previous.stop_after ? previous.dwell_after_s + settings_.stop_hold_s : 0.0;
  }
  if (last) point.hold_s = std::max(point.hold_s, settings_.stop_hold_s);
  if (Status solved = solve(point); !solved) {
    failed_in_workspace_ =
        solved.error().code == ErrorCode::unreachable || solved.error().code == ErrorCode::limit_exceeded;
    return solved;
  }
  ++count_;
  if (count_ >= 2) hand_on_caps(false);
  return ok_status();
}

Status PathSampler::solve(Point& point) {
  const Mechanism& mechanism = *machine_.mechanism;
  const path::Segment& seg = path_.segment(point.segment);
  const path::PathPoint on_path = path_.evaluate(point.segment, point.s);
  const Pose pose{on_path.position_mm, on_path.rotation.toRotationMatrix()};
  point.position_mm = on_path.position_mm;
  if (count_ % 4096 == 0 && settings_.total_lines > 0) {
    report_progress(settings_.progress, "planning",
                    std::min(1.0, static_cast<double>(seg.line) / settings_.total_lines), seg.line);
  }
  auto ik = mechanism.inverse(pose);
  if (!ik) {
    return at_line(
        source_, seg.line,
        Error{ErrorCode::unreachable, fmt::format("the path leaves the workspace at {}: {}",
                                                  program_pose_text(machine_, pose), ik.error().message)});
  }
  point.q = *ik;
  if (Status s = check_actuator_range(machine_, *ik); !s) return at_line(source_, seg.line, s.error());
  if (Status s = check_joint_limits(machine_, pose); !s) return at_line(source_, seg.line, s.error());
  if (point.s >= next_condition_check_ || point.last) {
    next_condition_check_ = point.s + settings_.condition_spacing;
    auto condition = jacobian_condition_number(mechanism, pose);
    if (condition) max_condition_ = std::max(max_condition_, *condition);
    const auto& limit = machine_.joint_limits.max_condition_number;
    if (!condition || (limit && !(*condition <= *limit))) {
      if (Status s = check_conditioning_limit(machine_, pose); !s)
        return at_line(source_, seg.line, s.error());
    }
  }
  return ok_status();
}

/// The caps of the sample before the last placed (or, at the path's end, of the last): the feed's, the
/// path's and the actuators'.
void PathSampler::hand_on_caps(bool last) {
  const std::size_t i = last ? count_ - 1 : count_ - 2;
  const Point& here = ring_[i % 3];
  const Point& before = ring_[(i + 2) % 3];  // sample i − 1 (unused at i = 0)
  const Point& after = ring_[(i + 1) % 3];   // sample i + 1 (unused at the end)
  Neighbours at{before.s, here.s, after.s, i > 0, !last};
  const MotionSettings& motion = machine_.motion;
  const path::Segment& seg = path_.segment(here.segment);
  double cap = segment_speed_cap(seg, motion, settings_.override_factor);
  if (i > 0 && before.segment != here.segment) {  // a boundary sample obeys both segments
    cap = std::min(cap, segment_speed_cap(path_.segment(before.segment), motion, settings_.override_factor));
  }
  DriveCapLimits limits;
  limits.margin = settings_.actuator_margin;
  limits.speed_max = machine_.limits.speed.value_or(std::numeric_limits<double>::infinity());
  limits.accel_max = machine_.limits.accel.value_or(std::numeric_limits<double>::infinity());
  limits.chord_tolerance_mm = settings_.chord_tolerance_mm;
  limits.period_s = settings_.period_s;
  if (!here.stop && !at.one_sided() && !seg.rotation_only) {
    cap = std::min(cap, curvature_cap(before.position_mm, here.position_mm, after.position_mm, at,
                                      motion.path_accel_mm_s2, limits));
  }
  const ActuatorCaps caps = actuator_caps(before.q, here.q, after.q, at, here.stop, limits);
  if (caps.speed < cap && !last) actuator_limited_length_ += after.s - here.s;
  cap = std::min(cap, caps.speed);
  SampledPoint out;
  out.segment = here.segment;
  out.raw.s = here.s;
  out.raw.speed_cap = here.stop ? 0.0 : cap;
  out.raw.accel_cap = std::min(motion.path_accel_mm_s2, caps.accel);
  out.raw.hold_s = here.hold_s;
  out.raw.stop = here.stop;
  out.raw.move = seg.move;
  ready_.push_back(out);
}

}  // namespace pkm::planning
