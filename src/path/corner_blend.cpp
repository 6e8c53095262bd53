#include "path/corner_blend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace pkm::path {

namespace {

Eigen::Vector3d blend_point(const Curve& a, const Curve& b, const Segment& seg, double u) {
  const Eigen::Vector3d pa = a.position(seg.fa0 + u * (seg.fa1 - seg.fa0));
  return pa + blend_weight(u) * (b.position(seg.fb0 + u * (seg.fb1 - seg.fb0)) - pa);
}

/// Unit tangent of the controlled point at fraction f, looking backward (end of a move) or forward.
Eigen::Vector3d tangent(const Curve& c, double f, bool backward) {
  const double df = std::min(1e-4, 1e-4 / std::max(c.translation_mm, 1e-9));
  const Eigen::Vector3d d =
      backward ? c.position(f) - c.position(f - df) : c.position(f + df) - c.position(f);
  return d.normalized();
}

/// Distance from `point` to curve `c` over fractions [f0, f1]. Lines: exact. Helices: the fraction of the
/// point's angle about the axis (exact for circles), then a few bracketing refinements for the helix pitch.
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
  } else {
    best_f = 0.5 * (f0 + f1);
  }
  double best = (c.position(best_f) - point).squaredNorm();
  if (c.kind == CurveKind::helix && c.axial_mm == 0.0 && c.tool_length_mm == 0.0) return std::sqrt(best);
  double step = 0.25 * (f1 - f0);
  for (int it = 0; it < 12; ++it) {
    for (double f : {best_f - step, best_f + step}) {
      if (f < f0 || f > f1) continue;
      const double d = (c.position(f) - point).squaredNorm();
      if (d < best) best = d, best_f = f;
    }
    step *= 0.5;
  }
  return std::sqrt(best);
}

double deviation(const Curve& a, const Curve& b, const Segment& blend) {
  double worst = 0.0;
  for (int k = 1; k < 12; ++k) {
    const Eigen::Vector3d p = blend_point(a, b, blend, k / 12.0);
    const double d =
        std::min(distance_to_curve(a, blend.fa0, 1.0, p), distance_to_curve(b, 0.0, blend.fb1, p));
    worst = std::max(worst, d);
  }
  return worst;
}

/// Arc-length parametrisation u(s) of the blend, and its length.
double fill_blend_table(const Curve& a, const Curve& b, const Segment& seg, BlendTable& table) {
  constexpr int fine = 48;
  constexpr std::size_t points = fine + 1;
  std::array<double, points> cumulative{};
  Eigen::Vector3d previous = blend_point(a, b, seg, 0.0);
  for (int k = 1; k <= fine; ++k) {
    const Eigen::Vector3d p = blend_point(a, b, seg, static_cast<double>(k) / fine);
    cumulative[k] = cumulative[k - 1] + (p - previous).norm();
    previous = p;
  }
  const double length = cumulative[fine];
  constexpr int last = kBlendKnots - 1;
  int j = 0;
  for (int k = 0; k <= last; ++k) {
    double u = 1.0;
    if (k == 0) {
      u = 0.0;
    } else if (k < last) {
      const double target = length * k / last;
      while (j + 1 < fine && cumulative[j + 1] < target) ++j;
      const double span = cumulative[j + 1] - cumulative[j];
      u = (j + (span > 0 ? (target - cumulative[j]) / span : 0.0)) / fine;
    }
    const double du = 1e-6;
    const double u0 = std::max(0.0, u - du), u1 = std::min(1.0, u + du);
    const double speed = (blend_point(a, b, seg, u1) - blend_point(a, b, seg, u0)).norm() / (u1 - u0);
    table.u[k] = u;
    table.du_ds[k] = length / speed;  // du/d(fraction of length)
  }
  return length;
}

}  // namespace

double blend_deviation_mm(const Path& path, int blend_index) {
  const Segment& seg = path.segments[blend_index];
  return deviation(path.curves[seg.curve_a], path.curves[seg.curve_b], seg);
}

void blend_corners(Path& path, double tolerance_mm) {
  if (path.segments.size() < 2) return;
  std::vector<Segment> out;
  out.reserve(path.segments.size() * 2);
  out.push_back(path.segments.front());
  for (std::size_t i = 1; i < path.segments.size(); ++i) {
    Segment next = path.segments[i];
    Segment& prev = out.back();
    const Curve& a = path.curves[prev.curve_a];
    const Curve& b = path.curves[next.curve_a];
    // The program's G64 P, where given, else the default; the tighter of the two moves'.
    auto tolerance_of = [tolerance_mm](const Segment& s) {
      return s.tolerance_mm > 0.0 ? s.tolerance_mm : tolerance_mm;
    };
    const double tolerance = std::min(tolerance_of(prev), tolerance_of(next));
    const bool joinable =
        tolerance > 0.0 && !prev.stop_after && !prev.is_blend() && !prev.rotation_only && !next.rotation_only;
    if (!joinable && !prev.stop_after && !prev.is_blend()) {
      // Not blendable: a corner needs a stop; a tangent join does not.
      const Eigen::Vector3d t1 = tangent(a, 1.0, true), t2 = tangent(b, 0.0, false);
      if (prev.rotation_only || next.rotation_only || std::acos(std::clamp(t1.dot(t2), -1.0, 1.0)) > 1e-7) {
        prev.stop_after = true;
      }
    }
    if (joinable) {
      const Eigen::Vector3d t1 = tangent(a, 1.0, true), t2 = tangent(b, 0.0, false);
      const double angle = std::acos(std::clamp(t1.dot(t2), -1.0, 1.0));
      if (angle > std::numbers::pi - 1e-3) {
        prev.stop_after = true;  // a reversal: stop and go back
      } else if (angle > 1e-7) {
        // The longest trim: half of either move (the other half may be trimmed by the next corner).
        const double max_trim = 0.5 * std::min(a.translation_mm, b.translation_mm);
        double trim = std::min(max_trim, 4.0 * tolerance / std::max(std::sin(0.5 * angle), 1e-6));
        Segment blend;
        blend.curve_a = prev.curve_a;
        blend.curve_b = next.curve_a;
        // The deviation grows in proportion to the trim (exactly so between lines): scale to the tolerance,
        // then halve until the sampled deviation is within it (arcs bend the proportion a little).
        auto set_trim = [&](double t) {
          blend.fa0 = 1.0 - t / a.translation_mm;
          blend.fa1 = 1.0;
          blend.fb0 = 0.0;
          blend.fb1 = t / b.translation_mm;
          return deviation(a, b, blend);
        };
        double dev = set_trim(trim);
        if (dev > 0.0) {
          trim = std::min(max_trim, trim * 0.98 * tolerance / dev);
          dev = set_trim(trim);
        }
        for (int halving = 0; halving < 30 && dev > tolerance; ++halving) dev = set_trim(trim *= 0.5);
        blend.blend = static_cast<int>(path.blend_tables.size());
        path.blend_tables.emplace_back();
        blend.length = fill_blend_table(a, b, blend, path.blend_tables.back());
        blend.turn_rad = angle;
        blend.line = prev.line;
        blend.move = prev.move;
        blend.rapid = prev.rapid && next.rapid;
        blend.speed_limit = std::min(prev.speed_limit, next.speed_limit);
        // Trim the two moves to the blend's ends; their lengths scale with the fraction (uniform curves).
        prev.length *= (blend.fa0 - prev.fa0) / (prev.fa1 - prev.fa0);
        prev.fa1 = blend.fa0;
        next.length *= (next.fa1 - blend.fb1) / (next.fa1 - next.fa0);
        next.fa0 = blend.fb1;
        out.push_back(blend);
      }
    }
    out.push_back(next);
  }
  // Trimming can leave a move with (almost) nothing between two blends; drop such slivers.
  std::erase_if(out, [](const Segment& s) { return !s.is_blend() && s.length <= 1e-12 && !s.stop_after; });
  path.segments = std::move(out);
}

}  // namespace pkm::path
