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

/// Fractions of a blend's length at which to sample it, in increasing order, without 0 (the segment's start
/// is a sample already) and with 1. A near-reversal turns almost all its angle in a short stretch around its
/// middle, where the cross-fade is slow: samples equally spaced in length (≤ 3° of turning each on average)
/// left two samples in that stretch, and the actuator curvature between them was underestimated by half
/// (a hexaglide reached 3015 of its 3000 mm/s²). So the need of each interval between the knots of the
/// blend's arc-length table (uniform in the cross-fade parameter, path.hpp) is measured: its turning in
/// 3° of the tool point's direction, in 1° of the platform's, its length in `spacing`; and the samples split
/// the blend into at least 4 pieces of equal need.
void blend_sample_fractions(const path::Path& path, int index, double spacing, std::vector<double>& out) {
  const path::Segment& seg = path.segment(index);
  const path::BlendTable& table = path.blend_table(seg.blend);
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
  const path::Segment& seg = path.segment(k);
  double pieces = std::ceil(seg.length / spacing);
  const path::Curve& curve = path.curve(seg.curve_a);
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
  const bool starts_at_rest = k == 0 || path.segment(k - 1).stop_after;
  if (starts_at_rest && seg.stop_after) pieces = std::max(pieces, 4.0);
  return std::max(pieces, 1.0);
}

}  // namespace

double segment_sample_positions(const path::Path& path, int k, double spacing, double max_count,
                                std::vector<double>& out) {
  out.clear();
  const path::Segment& seg = path.segment(k);
  if (seg.is_blend()) {
    blend_sample_fractions(path, k, spacing, out);
    out.pop_back();  // the end is the next segment's start
    for (double& f : out) f = seg.s_start + seg.length * f;
    out.insert(out.begin(), seg.s_start);
    return static_cast<double>(out.size());
  }
  const double pieces = move_pieces(path, k, spacing);
  if (pieces > max_count) return pieces;
  const int count = static_cast<int>(pieces);
  for (int i = 0; i < count; ++i) out.push_back(seg.s_start + seg.length * i / count);
  return pieces;
}

void whole_path_samples(const path::Path& path, double spacing, std::size_t max_samples,
                        std::vector<double>& s, std::vector<int>& segment) {
  s.clear();
  segment.clear();
  std::vector<double> places;
  for (int k = path.segment_base; k < path.segment_end(); ++k) {
    const double room = static_cast<double>(max_samples - s.size());
    if (segment_sample_positions(path, k, spacing, room, places) > room) {
      s.clear();
      segment.clear();
      return;
    }
    for (double place : places) {
      if (!s.empty() && place <= s.back()) continue;
      s.push_back(place);
      segment.push_back(k);
    }
  }
  if (path.segments.empty()) return;
  if (s.empty() || path.length() > s.back()) {
    s.push_back(path.length());
    segment.push_back(path.segment_end() - 1);
  }
}

}  // namespace pkm::planning
