#include "path/corner_blend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace pkm::path {

namespace {

// Two properties make a blend safe to follow, and both are checked on the blend itself, whatever the moves
// are (lines, arcs, helices, turning tools):
//  - deviation: every point within the tolerance of the two programmed moves (sampled at kProbeSamples);
//  - regularity: the parametric speed |dC/du| nowhere below kMinSpeedShare of its mean. Near a reversal the
//    cross-fade's velocity vanishes mid-blend (between lines its component along the bisector is
//    d·cos(θ/2)·(1 + w'(u))), the corner becomes a cusp the tool has to stop at anyway, and the arc-length
//    map u(s) would need an unbounded slope. Such a corner is an exact stop.
constexpr int kProbeSamples = 24;
constexpr double kMinSpeedShare = 0.2;

Eigen::Vector3d blend_point(const Curve& a, const Curve& b, const Segment& seg, double u) {
  const Eigen::Vector3d pa = a.position(seg.fa0 + u * (seg.fa1 - seg.fa0));
  return pa + blend_weight(u) * (b.position(seg.fb0 + u * (seg.fb1 - seg.fb0)) - pa);
}

/// dC/du of the cross-fade C(u) = A(u) + w(u)·(B(u) − A(u)).
Eigen::Vector3d blend_velocity(const Curve& a, const Curve& b, const Segment& seg, double u) {
  const double fa = seg.fa0 + u * (seg.fa1 - seg.fa0), fb = seg.fb0 + u * (seg.fb1 - seg.fb0);
  const Eigen::Vector3d va = a.velocity(fa) * (seg.fa1 - seg.fa0);
  const Eigen::Vector3d vb = b.velocity(fb) * (seg.fb1 - seg.fb0);
  return va + blend_weight(u) * (vb - va) + blend_weight_rate(u) * (b.position(fb) - a.position(fa));
}

/// Unit tangent of the controlled point at fraction f of a move.
Eigen::Vector3d tangent(const Curve& c, double f) {
  return c.velocity(f).normalized();
}

/// Distance from `point` to curve `c` over fractions [f0, f1]. Lines: exact. Helices: the fraction of the
/// point's angle about the axis (exact for circles); a turning tool: the nearest of nine points of the
/// window; then bracketing refinements (the helix pitch, the tool's swing).
double distance_to_curve(const Curve& c, double f0, double f1, const Eigen::Vector3d& point) {
  if (c.kind == CurveKind::line && c.tool_length_mm == 0.0) {  // exact: distance to the line piece
    const Eigen::Vector3d p0 = c.position(f0), p1 = c.position(f1);
    const Eigen::Vector3d d = p1 - p0;
    const double t = std::clamp((point - p0).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    return (p0 + t * d - point).norm();
  }
  double best_f = f0;
  if (c.kind == CurveKind::helix && c.sweep_rad > 0.0) {
    const Eigen::Vector3d r = point - c.centre_mm;
    double angle = std::atan2(r.dot(c.v), r.dot(c.u));
    if (angle < 0.0) angle += 2.0 * std::numbers::pi;
    // The turn of the helix nearest to the window's middle.
    const double middle = 0.5 * (f0 + f1) * c.sweep_rad;
    angle += 2.0 * std::numbers::pi * std::round((middle - angle) / (2.0 * std::numbers::pi));
    best_f = std::clamp(angle / c.sweep_rad, f0, f1);
  }
  double best = (c.position(best_f) - point).squaredNorm();
  if (c.kind == CurveKind::helix && c.axial_mm == 0.0 && c.tool_length_mm == 0.0) return std::sqrt(best);
  if (c.kind == CurveKind::line || c.tool_length_mm != 0.0) {
    // A turning tool bends the controlled point's curve: start from the nearest of a few points of the
    // window.
    for (int k = 0; k <= 8; ++k) {
      const double f = f0 + (f1 - f0) * k / 8.0;
      const double d = (c.position(f) - point).squaredNorm();
      if (d < best) best = d, best_f = f;
    }
  }
  double step = 0.125 * (f1 - f0);
  for (int it = 0; it < 16; ++it) {
    for (double f : {best_f - step, best_f + step}) {
      if (f < f0 || f > f1) continue;
      const double d = (c.position(f) - point).squaredNorm();
      if (d < best) best = d, best_f = f;
    }
    step *= 0.5;
  }
  return std::sqrt(best);
}

struct BlendProbe {
  double deviation_mm = 0.0;     ///< largest sampled distance from the two moves
  double min_speed_share = 0.0;  ///< smallest sampled |dC/du| over its mean (the blend's length)
};

double distance_to_moves(const Curve& a, const Curve& b, const Segment& blend, const Eigen::Vector3d& p) {
  return std::min(distance_to_curve(a, blend.fa0, 1.0, p), distance_to_curve(b, 0.0, blend.fb1, p));
}

/// `refine`: also search the largest deviation between the samples (for the final decision; the sizing steps
/// before it need only the samples).
BlendProbe probe(const Curve& a, const Curve& b, const Segment& blend, bool refine) {
  BlendProbe result;
  double length = 0.0, slowest = std::numeric_limits<double>::infinity();
  int worst = 0;
  Eigen::Vector3d previous = blend_point(a, b, blend, 0.0);
  for (int k = 0; k <= kProbeSamples; ++k) {
    const double u = static_cast<double>(k) / kProbeSamples;
    const Eigen::Vector3d p = blend_point(a, b, blend, u);
    length += (p - previous).norm();
    previous = p;
    slowest = std::min(slowest, blend_velocity(a, b, blend, u).norm());
    if (k == 0 || k == kProbeSamples) continue;  // the ends lie on the moves
    const double d = distance_to_moves(a, b, blend, p);
    if (d > result.deviation_mm) result.deviation_mm = d, worst = k;
  }
  // The largest deviation lies between the worst sample's neighbours: golden sections find it.
  double lo = std::max(0, worst - 1) / static_cast<double>(kProbeSamples);
  double hi = std::min(kProbeSamples, worst + 1) / static_cast<double>(kProbeSamples);
  for (int it = 0; it < 12 && worst > 0 && refine; ++it) {
    const double m1 = hi - 0.618 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    const double d1 = distance_to_moves(a, b, blend, blend_point(a, b, blend, m1));
    const double d2 = distance_to_moves(a, b, blend, blend_point(a, b, blend, m2));
    result.deviation_mm = std::max({result.deviation_mm, d1, d2});
    if (d1 > d2)
      hi = m2;
    else
      lo = m1;
  }
  result.min_speed_share = length > 0.0 ? slowest / length : 0.0;
  return result;
}

/// Arc-length parametrisation u(s) of the blend, and its length: at knots uniform in u, the arc length
/// (Gauss– Legendre on |dC/du|, three points per knot piece) and the slope du/ds. The slopes are limited to
/// three times the neighbouring secants (the Fritsch–Carlson condition), so every cubic Hermite piece of u(s)
/// is monotone and stays between its knots: an evaluated point is always a point of the blend, never beyond
/// its ends. Returns the length and the largest tool speed over planned speed |dC/ds| at the pieces' middles
/// (1 for an exact map; the blend's speed limit is divided by it, so that the tool keeps the programmed
/// feed).
struct BlendMap {
  double length = 0.0;
  double max_speed_ratio = 1.0;
};
BlendMap fill_blend_table(const Curve& a, const Curve& b, const Segment& seg, BlendTable& table) {
  constexpr int last = kBlendKnots - 1;
  constexpr double du = 1.0 / last;
  const double node = 0.5 / std::sqrt(3.0);  // Gauss–Legendre nodes at the middle ± this (of the piece)
  std::array<double, kBlendKnots> speed{};
  table.s[0] = 0.0;
  for (int k = 0; k <= last; ++k) {
    const double u = k * du;
    speed[k] = blend_velocity(a, b, seg, u).norm();
    if (k == last) break;
    const double mid = u + 0.5 * du;
    const double piece = 0.5 * du *
                         (blend_velocity(a, b, seg, mid - node * du).norm() +
                          blend_velocity(a, b, seg, mid + node * du).norm());
    table.s[k + 1] = table.s[k] + piece;
  }
  const double length = table.s[last];
  if (!(length > 0.0)) return {};
  for (double& s : table.s) s /= length;
  table.s[last] = 1.0;
  for (int k = 0; k <= last; ++k) table.du_ds[k] = length / std::max(speed[k], 1e-300);
  for (int k = 0; k <= last; ++k) {
    const double before = k > 0 ? du / (table.s[k] - table.s[k - 1]) : table.du_ds[k];
    const double after = k < last ? du / (table.s[k + 1] - table.s[k]) : table.du_ds[k];
    table.du_ds[k] = std::clamp(table.du_ds[k], 0.0, 3.0 * std::min(before, after));
  }
  BlendMap map{length, 1.0};
  for (int k = 0; k < last; ++k) {  // the Hermite piece at t = 1/2: u and du/d(fraction) there
    const double h = table.s[k + 1] - table.s[k];
    const double u = (k + 0.5) * du + h * (table.du_ds[k] - table.du_ds[k + 1]) / 8.0;
    const double slope = 1.5 * du / h - 0.25 * (table.du_ds[k] + table.du_ds[k + 1]);
    map.max_speed_ratio = std::max(map.max_speed_ratio, blend_velocity(a, b, seg, u).norm() * slope / length);
  }
  return map;
}

/// The blend of the last `trim` of move `a` and the first `trim` of move `b` (in mm of tool-point travel).
Segment blend_window(const Segment& prev, const Segment& next, const Curve& a, const Curve& b, double trim) {
  Segment blend;
  blend.curve_a = prev.curve_a;
  blend.curve_b = next.curve_a;
  blend.fa0 = 1.0 - trim / a.translation_mm;
  blend.fa1 = 1.0;
  blend.fb0 = 0.0;
  blend.fb1 = trim / b.translation_mm;
  return blend;
}

/// The largest blend of the corner between `prev` and `next` within `tolerance_mm`, or nothing where no
/// blend can be both within the tolerance and regular (a reversal, or geometry too small to blend).
std::optional<Segment> corner_blend(const Segment& prev, const Segment& next, const Curve& a, const Curve& b,
                                    double angle, double tolerance_mm) {
  // Each move gives at most half of itself (its other half may go to the blend at its other end).
  const double max_trim = 0.5 * std::min(a.translation_mm, b.translation_mm);
  double trim = std::min(max_trim, 4.0 * tolerance_mm / std::max(std::sin(0.5 * angle), 1e-6));
  Segment blend = blend_window(prev, next, a, b, trim);
  BlendProbe shape = probe(a, b, blend, false);
  // Between lines the deviation is proportional to the trim: scale to just inside the tolerance, then halve
  // while the deviation is over it (arcs bend the proportion a little).
  if (shape.deviation_mm > 0.0) {
    trim = std::min(max_trim, trim * 0.95 * tolerance_mm / shape.deviation_mm);
    blend = blend_window(prev, next, a, b, trim);
  }
  shape = probe(a, b, blend, true);
  for (int halving = 0; halving < 30 && shape.deviation_mm > tolerance_mm; ++halving) {
    trim *= 0.5;
    blend = blend_window(prev, next, a, b, trim);
    shape = probe(a, b, blend, true);
  }
  if (shape.deviation_mm > tolerance_mm || shape.min_speed_share < kMinSpeedShare) return std::nullopt;
  return blend;
}

}  // namespace

double blend_deviation_mm(const Path& path, int blend_index) {
  const Segment& seg = path.segment(blend_index);
  return probe(path.curve(seg.curve_a), path.curve(seg.curve_b), seg, true).deviation_mm;
}

std::optional<Segment> join_corner(Path& path, Segment& prev, Segment& next, double tolerance_mm) {
  const Curve& a = path.curve(prev.curve_a);
  const Curve& b = path.curve(next.curve_a);
  if (prev.rotation_only || next.rotation_only) prev.stop_after = true;  // turning: no blend joins it
  if (prev.stop_after) return std::nullopt;
  const double angle = std::acos(std::clamp(tangent(a, 1.0).dot(tangent(b, 0.0)), -1.0, 1.0));
  // A join is smooth only where the tool point keeps its direction and the platform its turning rate per
  // mm: a line that starts tilting where a tangent arc ends is a corner for the struts (their speed jumps).
  const double rate_jump_rad_mm =
      (a.angular_rate() / a.translation_mm - b.angular_rate() / b.translation_mm).norm();
  if (angle <= 1e-7 && rate_jump_rad_mm <= 1e-9) return std::nullopt;  // smooth: no blend, no stop
  // The program's G64 P, where given, else the default; the tighter of the two moves'.
  auto tolerance_of = [tolerance_mm](const Segment& s) {
    return s.tolerance_mm > 0.0 ? s.tolerance_mm : tolerance_mm;
  };
  const double tolerance = std::min(tolerance_of(prev), tolerance_of(next));
  std::optional<Segment> blend;
  if (tolerance > 0.0) blend = corner_blend(prev, next, a, b, angle, tolerance);
  if (!blend) {
    prev.stop_after = true;  // a corner: stop and turn
    return std::nullopt;
  }
  blend->blend = path.blend_base + static_cast<int>(path.blend_tables.size());
  path.blend_tables.emplace_back();
  const BlendMap map = fill_blend_table(a, b, *blend, path.blend_tables.back());
  blend->length = map.length;
  blend->turn_rad = angle;
  blend->line = prev.line;
  blend->move = prev.move;
  blend->rapid = prev.rapid && next.rapid;
  blend->speed_limit = std::min(prev.speed_limit, next.speed_limit) / map.max_speed_ratio;
  // Trim the two moves to the blend's ends; their lengths scale with the fraction (uniform curves).
  prev.length *= (blend->fa0 - prev.fa0) / (prev.fa1 - prev.fa0);
  prev.fa1 = blend->fa0;
  next.length *= (next.fa1 - blend->fb1) / (next.fa1 - next.fa0);
  next.fa0 = blend->fb1;
  return blend;
}

bool is_sliver(const Segment& segment) {
  return !segment.is_blend() && segment.length <= 1e-12 && !segment.stop_after;
}

void blend_corners(Path& path, double tolerance_mm) {
  if (path.segments.size() < 2) return;
  std::vector<Segment> out;
  out.reserve(path.segments.size() * 2);
  out.push_back(path.segments.front());
  for (std::size_t i = 1; i < path.segments.size(); ++i) {
    Segment next = path.segments[i];
    // `out` never reallocates (reserved for every move and a blend between each), so its back stays valid.
    if (std::optional<Segment> blend = join_corner(path, out.back(), next, tolerance_mm))
      out.push_back(*blend);
    out.push_back(next);
  }
  // Trimming can leave a move with (almost) nothing between two blends; drop such slivers.
  std::erase_if(out, is_sliver);
  path.segments = std::move(out);
}

}  // namespace pkm::path
