#pragma once
// The geometric tool path of a whole program: moves as curves (curve.hpp), joined by corner blends, all on
// one continuous path parameter s (mm of tool-point travel; degrees along moves that only rotate).
// Every segment keeps the source line of the move it came from, so any later problem names the program line.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "path/curve.hpp"

namespace pkm::path {

/// Knots of the arc-length parametrisation of a corner blend: u(s) by cubic Hermite pieces between knots at
/// u = k/(kBlendKnots − 1). Uniform in u, the knots crowd in s where the blend is slow (a sharp corner's
/// middle), which is where u(s) bends most.
constexpr int kBlendKnots = 17;
struct BlendTable {
  std::array<double, kBlendKnots> s{};      ///< fraction of the blend's length at u = k/(kBlendKnots − 1)
  std::array<double, kBlendKnots> du_ds{};  ///< du/d(fraction of length) there
};

struct Segment {
  int curve_a = 0;              ///< the move's curve (blends: the incoming move)
  int curve_b = -1;             ///< blends only: the outgoing move's curve
  double fa0 = 0.0, fa1 = 1.0;  ///< window of curve_a's fraction covered by this segment
  double fb0 = 0.0, fb1 = 0.0;  ///< blends: window of curve_b's fraction
  int blend = -1;               ///< index into Path::blend_tables, or −1 for a plain piece of one move
  double s_start = 0.0;
  double length = 0.0;  ///< in path-parameter units (mm, or deg for rotation-only moves)
  int line = 0;         ///< source line (blends: the incoming move's)
  int move = 0;         ///< index of the canonical move (blends: the incoming move)
  bool rapid = false;
  bool rotation_only = false;
  double speed_limit = 0.0;    ///< programmed speed at 100 % override, path units per second
  double tolerance_mm = -1.0;  ///< G64 P in effect (−1: the planner's default)
  double turn_rad = 0.0;       ///< blends: the angle between the two moves' directions at the corner
  bool stop_after = false;     ///< the motion comes to rest at the end of this segment
  double dwell_after_s = 0.0;
  bool is_blend() const { return blend >= 0; }
};

struct PathPoint {
  Eigen::Vector3d position_mm;
  Eigen::Quaterniond rotation;
};

/// A whole path, or a window of one that a streaming planner appends to and drops behind it: the vectors
/// then hold the segments from `segment_base` on (and the curves and blend tables from their bases), while
/// every index (a segment's curves and blend, a hint, the planner's sample segments) stays the whole path's.
/// A whole path has every base 0, so its vectors can be indexed directly.
class Path {
 public:
  std::vector<Curve> curves;
  std::vector<Segment> segments;
  std::vector<BlendTable> blend_tables;
  int segment_base = 0, curve_base = 0, blend_base = 0;
  double initial_dwell_s = 0.0;
  PathPoint start;  ///< where the path starts (also the whole path when there are no segments)

  const Segment& segment(int index) const { return segments[index - segment_base]; }
  const Curve& curve(int index) const { return curves[index - curve_base]; }
  const BlendTable& blend_table(int index) const { return blend_tables[index - blend_base]; }
  /// One past the last segment's index.
  int segment_end() const { return segment_base + static_cast<int>(segments.size()); }
  double length() const { return segments.empty() ? 0.0 : segments.back().s_start + segments.back().length; }
  /// Index of the segment containing s, searching forward from `hint` (monotone use is O(1)).
  int find_segment(double s, int hint) const;
  /// The pose at s on segment `index` (s is clamped to the segment).
  PathPoint evaluate(int index, double s) const;
  PathPoint evaluate(double s, int& hint) const { return evaluate(hint = find_segment(s, hint), s); }
  PathPoint end_point() const;
  /// Forgets the segments before `index` and the curves and blend tables only they use. Amortised O(1):
  /// the vectors are compacted once what is forgotten is at least half of them.
  void drop_before(int index);
};

/// The blend weight: 0 → 1 with zero first and second derivative at both ends (curvature-continuous joins).
inline double blend_weight(double u) {
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}
/// dw/du = 30·u²·(1 − u)².
inline double blend_weight_rate(double u) {
  const double v = u * (1.0 - u);
  return 30.0 * v * v;
}

}  // namespace pkm::path
