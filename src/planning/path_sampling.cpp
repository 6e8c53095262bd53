#include "planning/path_sampling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "machine/joint_limits.hpp"
#include "planning/workspace_excursion.hpp"

namespace pkm::planning {

std::string program_pose_text(const Machine& machine, const Pose& pose) {
  const Eigen::Vector3d p = pose.position_mm - machine.motion.program_origin_mm;
  const Eigen::Vector3d abc = angles_from_rotation(AngleConvention::abc, pose.rotation) * (180.0 / kPi);
  return fmt::format("X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} B{:.4f} C{:.4f}", p.x(), p.y(), p.z(), abc.x(), abc.y(),
                     abc.z());
}

double segment_speed_cap(const path::Segment& segment, const MotionSettings& motion, double override_factor) {
  const double machine_cap = segment.rotation_only ? motion.angular_feed_deg_min / 60.0
                             : segment.rapid       ? motion.rapid_mm_min / 60.0
                                                   : motion.max_feed_mm_min / 60.0;
  return std::min(segment.speed_limit * override_factor, machine_cap);
}

namespace {

constexpr double kCurvatureShare = 0.5;  // α: share of the actuator acceleration left for the v²·q'' term

Error at_line(const program::CanonicalProgram& program, int line, const Error& error) {
  return Error{error.code, fmt::format("{}:{}: {}", program.source, line, error.message),
               ErrorLocation{program.source, line, 0, ""}};
}

/// Fractions of a blend's length at which to sample it, in increasing order, without 0 (the segment's start
/// is a sample already) and with 1. A near-reversal turns almost all its angle in a short stretch around its
/// middle, where the cross-fade is slow: samples equally spaced in length (≤ 3° of turning each on average)
/// left two samples in that stretch, and the actuator curvature between them was underestimated by half
/// (a hexaglide reached 3015 of its 3000 mm/s²). So the need of each interval between the knots of the
/// blend's arc-length table (uniform in the cross-fade parameter, path.hpp) is measured: its turning in
/// 3° of the tool point's direction, in 1° of the platform's, its length in `spacing`; and the samples split
/// the blend into at least 4 pieces of equal need.
void blend_sample_fractions(const path::Path& path, int index, double spacing, std::vector<double>& out) {
  const path::Segment& seg = path.segments[index];
  const path::BlendTable& table = path.blend_tables[seg.blend];
  std::array<path::PathPoint, path::kBlendKnots> knot;
  for (int k = 0; k < path::kBlendKnots; ++k)
    knot[k] = path.evaluate(index, seg.s_start + seg.length * table.s[k]);
  // Turning at knot k between the chords on either side, shared by the two intervals that meet there.
  std::array<double, path::kBlendKnots - 1> turn_rad{};
  for (int k = 1; k + 1 < path::kBlendKnots; ++k) {
    const Eigen::Vector3d before = knot[k].position_mm - knot[k - 1].position_mm;
    const Eigen::Vector3d after = knot[k + 1].position_mm - knot[k].position_mm;
    if (before.norm() > 0.0 && after.norm() > 0.0) {
      const double angle = std::atan2(before.cross(after).norm(), before.dot(after));
      turn_rad[k - 1] += 0.5 * angle;
      turn_rad[k] += 0.5 * angle;
    }
  }
  // How many pieces each interval needs (fractional), then pieces of equal need: dense where the blend turns.
  std::array<double, path::kBlendKnots> cumulative{};
  for (int k = 0; k + 1 < path::kBlendKnots; ++k) {
    const double rotation_rad = knot[k].rotation.angularDistance(knot[k + 1].rotation);
    const double need = std::max({seg.length * (table.s[k + 1] - table.s[k]) / spacing,
                                  turn_rad[k] / rad_from_deg(3.0), rotation_rad / rad_from_deg(1.0)});
    cumulative[k + 1] = cumulative[k] + need;
  }
  const double total = cumulative.back();
  const int pieces = std::max(4, static_cast<int>(std::ceil(total)));
  out.clear();
  int k = 0;
  for (int i = 1; i < pieces; ++i) {
    if (!(total > 0.0)) {
      out.push_back(static_cast<double>(i) / pieces);
      continue;
    }
    const double target = total * i / pieces;
    while (k + 2 < path::kBlendKnots && cumulative[k + 1] < target) ++k;
    const double width = cumulative[k + 1] - cumulative[k];
    const double t = width > 0.0 ? (target - cumulative[k]) / width : 0.0;
    out.push_back(table.s[k] + (table.s[k + 1] - table.s[k]) * t);
  }
  out.push_back(1.0);
}

/// The number of pieces a move (not a blend) is sampled in: no longer than `spacing`, at most 5° of an arc
/// and 1° of the platform's turning each. In double: a huge move must be refused, not overflow an int.
double move_pieces(const path::Path& path, int k, double spacing) {
  const path::Segment& seg = path.segments[k];
  double pieces = std::ceil(seg.length / spacing);
  const path::Curve& curve = path.curves[seg.curve_a];
  if (curve.kind == path::CurveKind::helix) {
    const double sweep = curve.sweep_rad * (seg.fa1 - seg.fa0);
    pieces = std::max(pieces, std::ceil(sweep / rad_from_deg(5.0)));
  }
  // The platform's turning bends the actuator curves as much as the tool point's path does (more, where the
  // tool point hardly moves while the platform tilts): at most 1° of turning per piece.
  const double turned_rad = curve.rotation_angle_rad * (seg.fa1 - seg.fa0);
  pieces = std::max(pieces, std::ceil(turned_rad / rad_from_deg(1.0)));
  // A move that starts and ends at rest (between two exact stops, as a short step between reversals) needs
  // a sample inside, where the profile turns from speeding up to braking: two samples both at rest would
  // have the motion cover the move in no time. Three inside: such moves are short and their actuator
  // derivatives come from few samples (a 0.01 mm 5-axis back-step was 6 % over its estimate with one).
  const bool starts_at_rest = k == 0 || path.segments[k - 1].stop_after;
  if (starts_at_rest && seg.stop_after) pieces = std::max(pieces, 4.0);
  return std::max(pieces, 1.0);
}

Error too_many_samples(const program::CanonicalProgram& program, int line, double needed, std::size_t bound) {
  return Error{
      ErrorCode::limit_exceeded,
      fmt::format("{}:{}: the path needs {:.3g} planning samples by the end of this line, over the bound "
                  "of {} (one every sample spacing, 5 deg of an arc and 1 deg of turning); raise "
                  "--max-samples to plan it",
                  program.source, line, needed, bound),
      ErrorLocation{program.source, line, 0, ""}};
}

/// Sample positions: every segment split into move_pieces (blends: blend_sample_fractions); the segment ends
/// are samples. Refused, before the memory is taken, when they would be more than `max_samples`.
Status place_samples(const program::CanonicalProgram& program, const path::Path& path, double spacing,
                     std::size_t max_samples, ProfileSamples& samples, std::vector<int>& segment) {
  samples.s.clear();
  segment.clear();
  samples.s.reserve(std::min(max_samples, path.segments.size() * 3 + 1));
  segment.reserve(std::min(max_samples, path.segments.size() * 3 + 1));
  std::vector<double> fractions;
  auto add = [&](double s, int k) {
    if (!samples.s.empty() && s <= samples.s.back()) return;
    samples.s.push_back(s);
    segment.push_back(k);
  };
  for (int k = 0; k < static_cast<int>(path.segments.size()); ++k) {
    const path::Segment& seg = path.segments[k];
    if (seg.is_blend()) {
      add(seg.s_start, k);
      blend_sample_fractions(path, k, spacing, fractions);
      fractions.pop_back();  // the end is the next segment's start
      for (double f : fractions) add(seg.s_start + seg.length * f, k);
      continue;
    }
    const double pieces = move_pieces(path, k, spacing);
    if (static_cast<double>(samples.s.size()) + pieces > static_cast<double>(max_samples))
      return too_many_samples(program, seg.line, static_cast<double>(samples.s.size()) + pieces, max_samples);
    const int count = static_cast<int>(pieces);
    for (int i = 0; i < count; ++i) add(seg.s_start + seg.length * i / count, k);
  }
  const double end = path.length();
  if (samples.s.empty() || end > samples.s.back()) {
    samples.s.push_back(end);
    segment.push_back(std::max(0, static_cast<int>(path.segments.size()) - 1));
  }
  samples.resize(samples.s.size());
  return ok_status();
}

/// Derivatives of a sampled function at sample i from its neighbours (non-uniform central differences);
/// at the ends and at stops, one-sided.
struct Derivatives {
  double first = 0.0;
  double second = 0.0;
};
Derivatives differentiate(double s0, double s1, double s2, double f0, double f1, double f2) {
  const double h1 = s1 - s0, h2 = s2 - s1;
  const double d1 = (f1 - f0) / h1, d2 = (f2 - f1) / h2;
  return {(h2 * d1 + h1 * d2) / (h1 + h2), 2.0 * (d2 - d1) / (h1 + h2)};
}

// Stops: the end of a segment that must come to rest (corners without blends, dwells, the program end), with
// the time to hold there.
void mark_stops(const path::Path& path, const std::vector<int>& sample_segment, double stop_hold_s,
                ProfileSamples& samples) {
  const std::size_t n = samples.size();
  std::vector<char>& stop = samples.stop;
  stop.assign(n, 0);
  stop[0] = 1;
  stop[n - 1] = 1;
  samples.hold_s.assign(n, 0.0);
  samples.hold_s[0] = path.initial_dwell_s;
  for (std::size_t i = 1; i < n; ++i) {
    const path::Segment& previous = path.segments[sample_segment[i - 1]];
    const bool boundary = i == n - 1 || sample_segment[i] != sample_segment[i - 1];
    if (boundary && previous.stop_after) {
      stop[i] = 1;
      samples.hold_s[i] += previous.dwell_after_s + stop_hold_s;
    }
  }
  if (samples.hold_s[n - 1] < stop_hold_s) samples.hold_s[n - 1] = stop_hold_s;
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

// The caps of the header's formulas from q' and q'' by finite differences over samples i − 1, i, i + 1.
ActuatorCaps actuator_caps(const ActuatorVector& q0, const ActuatorVector& q1, const ActuatorVector& q2,
                           const ProfileSamples& samples, std::size_t i, const DriveCapLimits& limits) {
  const std::size_t n = samples.size();
  const bool one_sided = i == 0 || samples.stop[i] || i + 1 == n;
  ActuatorCaps caps;
  for (int j = 0; j < q1.size(); ++j) {
    double first = 0.0, second = 0.0;
    if (one_sided) {
      // One-sided slopes; at a stop the larger of the two sides governs the acceleration there.
      if (i > 0) first = std::abs((q1[j] - q0[j]) / (samples.s[i] - samples.s[i - 1]));
      if (i + 1 < n) first = std::max(first, std::abs((q2[j] - q1[j]) / (samples.s[i + 1] - samples.s[i])));
    } else {
      const Derivatives d =
          differentiate(samples.s[i - 1], samples.s[i], samples.s[i + 1], q0[j], q1[j], q2[j]);
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
// samples i − 1, i, i + 1): the normal acceleration κ·v² ≤ a_path and the chord error between servo periods.
double curvature_cap(const std::array<Eigen::Vector3d, 3>& position_ring, const ProfileSamples& samples,
                     std::size_t i, double path_accel_mm_s2, const DriveCapLimits& limits) {
  Eigen::Vector3d second;
  for (int c = 0; c < 3; ++c) {
    second[c] = differentiate(samples.s[i - 1], samples.s[i], samples.s[i + 1], position_ring[(i + 2) % 3][c],
                              position_ring[i % 3][c], position_ring[(i + 1) % 3][c])
                    .second;
  }
  const double curvature = second.norm();
  if (!(curvature > 1e-12)) return std::numeric_limits<double>::infinity();
  return std::min(std::sqrt(path_accel_mm_s2 / curvature),
                  std::sqrt(8.0 * limits.chord_tolerance_mm / curvature) / limits.period_s);
}

}  // namespace

Result<SamplingResult> sample_path(const Machine& machine, const program::CanonicalProgram& program,
                                   const path::Path& path, const SamplingSettings& settings,
                                   ProfileSamples& samples, std::vector<int>& sample_segment) {
  SamplingResult result;
  const Mechanism& mechanism = *machine.mechanism;
  const MotionSettings& motion = machine.motion;
  if (Status placed =
          place_samples(program, path, settings.spacing, settings.max_samples, samples, sample_segment);
      !placed)
    return placed.error();
  const std::size_t n = samples.size();

  mark_stops(path, sample_segment, settings.stop_hold_s, samples);
  const std::vector<char>& stop = samples.stop;

  // Inverse kinematics and the position limits at every sample, one sample ahead of the caps (which need
  // i − 1, i, i + 1): a ring of three keeps memory independent of the program's length.
  std::array<ActuatorVector, 3> q_ring;
  std::array<Eigen::Vector3d, 3> position_ring;
  double next_condition_check = 0.0;
  auto solve = [&](std::size_t i) -> Status {
    const path::Segment& seg = path.segments[sample_segment[i]];
    const path::PathPoint point = path.evaluate(sample_segment[i], samples.s[i]);
    const Pose pose{point.position_mm, point.rotation.toRotationMatrix()};
    position_ring[i % 3] = point.position_mm;
    if (i % 4096 == 0) report_progress(settings.progress, "planning", static_cast<double>(i) / n, seg.line);
    auto ik = mechanism.inverse(pose);
    if (!ik) {
      return at_line(
          program, seg.line,
          Error{ErrorCode::unreachable, fmt::format("the path leaves the workspace at {}: {}",
                                                    program_pose_text(machine, pose), ik.error().message)});
    }
    q_ring[i % 3] = *ik;
    if (Status s = check_actuator_range(machine, *ik); !s) return at_line(program, seg.line, s.error());
    if (Status s = check_joint_limits(machine, pose); !s) return at_line(program, seg.line, s.error());
    if (samples.s[i] >= next_condition_check || i == n - 1) {
      next_condition_check = samples.s[i] + settings.condition_spacing;
      auto condition = jacobian_condition_number(mechanism, pose);
      if (condition) {
        result.statistics.max_condition_number = std::max(result.statistics.max_condition_number, *condition);
      }
      const auto& limit = machine.joint_limits.max_condition_number;
      if (!condition || (limit && !(*condition <= *limit))) {
        if (Status s = check_conditioning_limit(machine, pose); !s)
          return at_line(program, seg.line, s.error());
      }
    }
    return ok_status();
  };
  // Out of reach or past a position limit: the first sample's error, then the whole extent of the program's
  // excursions (the user moving the part needs all of it).
  const auto refuse = [&](const Error& first) -> Error {
    if (first.code != ErrorCode::unreachable && first.code != ErrorCode::limit_exceeded) return first;
    const WorkspaceExcursions found = find_excursions(machine, path, samples.s, sample_segment);
    if (found.excursions.empty()) return first;  // e.g. the conditioning limit: not a place to move away from
    Error whole = first;
    whole.message += "; " + describe_excursions(found);
    whole.details_json = excursions_json(found);
    return whole;
  };
  if (Status s = solve(0); !s) return refuse(s.error());

  // Caps from the feed, the path and the actuators.
  DriveCapLimits limits;
  limits.margin = settings.actuator_margin;
  limits.speed_max = machine.limits.speed.value_or(std::numeric_limits<double>::infinity());
  limits.accel_max = machine.limits.accel.value_or(std::numeric_limits<double>::infinity());
  limits.chord_tolerance_mm = settings.chord_tolerance_mm;
  limits.period_s = settings.period_s;
  double actuator_limited_length = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i + 1 < n) {
      if (Status s = solve(i + 1); !s) return refuse(s.error());
    }
    const ActuatorVector& q0 = q_ring[(i + 2) % 3];  // sample i − 1 (unused at i = 0)
    const ActuatorVector& q1 = q_ring[i % 3];
    const ActuatorVector& q2 = q_ring[(i + 1) % 3];  // sample i + 1 (unused at the end)
    const path::Segment& seg = path.segments[sample_segment[i]];
    double cap_feed = segment_speed_cap(seg, motion, settings.override_factor);
    if (i > 0 && sample_segment[i - 1] != sample_segment[i]) {  // a boundary sample obeys both segments
      cap_feed = std::min(cap_feed, segment_speed_cap(path.segments[sample_segment[i - 1]], motion,
                                                      settings.override_factor));
    }
    double cap = cap_feed;
    double accel_cap = motion.path_accel_mm_s2;
    if (!stop[i] && i > 0 && i + 1 < n && !seg.rotation_only)
      cap = std::min(cap, curvature_cap(position_ring, samples, i, motion.path_accel_mm_s2, limits));
    const ActuatorCaps caps = actuator_caps(q0, q1, q2, samples, i, limits);
    const double cap_actuator = caps.speed;
    accel_cap = std::min(accel_cap, caps.accel);
    if (cap_actuator < cap && i + 1 < n) actuator_limited_length += samples.s[i + 1] - samples.s[i];
    cap = std::min(cap, cap_actuator);
    samples.speed_cap[i] = stop[i] ? 0.0 : cap;
    samples.accel_cap[i] = accel_cap;
  }
  const double total = path.length();
  result.statistics.actuator_limited_fraction = total > 0 ? actuator_limited_length / total : 0.0;
  return result;
}

}  // namespace pkm::planning
