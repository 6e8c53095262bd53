#include "path/surface_strategies.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pkm::path {
namespace {

constexpr double kStrategyTwoPi = 2.0 * std::numbers::pi;

using StrategyPolyline = std::vector<Eigen::Vector2d>;

// The projected gaps that keep the surface distances within the options (see the header).
struct StrategyLayout {
  EllipsoidCap cap;
  double outline_x_mm = 0.0;  // A: the outline's semi-axis along x
  double outline_y_mm = 0.0;  // B
  double pass_gap_mm = 0.0;   // d = step-over · cos(tilt_max)
  double point_gap_mm = 0.0;  // p = spacing · cos(tilt_max)
  int dense_samples = 0;      // chords of a closed loop, for its arc length
};

StrategyLayout strategy_layout(const EllipsoidCap& cap, const StrategyOptions& options) {
  StrategyLayout layout;
  layout.cap = cap;
  const Eigen::Vector2d outline = cap_outline_semi_axes_mm(cap);
  layout.outline_x_mm = outline.x();
  layout.outline_y_mm = outline.y();
  const double cosine = std::cos(cap_max_tilt_rad(cap));
  layout.pass_gap_mm = options.step_over_mm * cosine;
  layout.point_gap_mm = options.spacing_mm * cosine;
  // Eight chords per point of a loop: the points' parameters come from the chords' arc length, which is then
  // within a small fraction of the curve's, so the points come out about equally spaced.
  const double perimeter_bound = kStrategyTwoPi * outline.maxCoeff();
  layout.dense_samples = 2 * static_cast<int>(std::ceil(4.0 * perimeter_bound / layout.point_gap_mm)) + 256;
  return layout;
}

// Appends at(t) for t in (ta, tb], with points in between where the two ends lie more than `max_step` apart.
template <class PointAt>
void append_refined(StrategyPolyline& out, const PointAt& at, double ta, const Eigen::Vector2d& a, double tb,
                    const Eigen::Vector2d& b, double max_step, int depth) {
  if ((b - a).norm() > max_step && depth < 40) {
    const double tm = 0.5 * (ta + tb);
    const Eigen::Vector2d m = at(tm);
    append_refined(out, at, ta, a, tm, m, max_step, depth + 1);
    append_refined(out, at, tm, m, tb, b, max_step, depth + 1);
    return;
  }
  out.push_back(b);
}

// Points of the curve at(t), t0 ≤ t ≤ t1, both ends included, at most `max_step` apart and about equally
// spaced: the parameters come from the arc length of `samples` chords, the points from the curve itself (so
// they lie on it exactly), and a step the chords made too long is split.
template <class PointAt>
StrategyPolyline curve_points(const PointAt& at, double t0, double t1, int samples, double max_step) {
  StrategyPolyline dense;
  dense.reserve(static_cast<std::size_t>(samples) + 1);
  std::vector<double> along(static_cast<std::size_t>(samples) + 1, 0.0);
  for (int i = 0; i <= samples; ++i) {
    dense.push_back(at(t0 + (t1 - t0) * i / samples));
    if (i > 0) along[i] = along[i - 1] + (dense[i] - dense[i - 1]).norm();
  }
  const int steps = std::max(1, static_cast<int>(std::ceil(along.back() / max_step)));
  StrategyPolyline out{dense.front()};
  out.reserve(static_cast<std::size_t>(steps) + 1);
  double previous_t = t0;
  std::size_t i = 1;
  for (int k = 1; k <= steps; ++k) {
    double t = t1;
    if (k < steps) {
      const double target = along.back() * k / steps;
      while (i + 1 < along.size() && along[i] < target) ++i;
      const double piece = along[i] - along[i - 1];
      const double f = piece > 0.0 ? (target - along[i - 1]) / piece : 0.0;
      t = t0 + (t1 - t0) * (static_cast<double>(i - 1) + f) / samples;
    }
    const Eigen::Vector2d from = out.back();
    append_refined(out, at, previous_t, from, t, at(t), max_step, 0);
    previous_t = t;
  }
  return out;
}

// A straight segment at most `max_step` between points, an even number of steps (a diameter then has its
// midpoint, the pole, as a point); with `ends` false only its inner points (a link between two passes).
StrategyPolyline straight_points(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double max_step,
                                 bool ends) {
  int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / max_step)));
  if (steps % 2 == 1 && ends) ++steps;
  StrategyPolyline out;
  for (int k = ends ? 0 : 1; k <= (ends ? steps : steps - 1); ++k)
    out.push_back(from + (to - from) * (static_cast<double>(k) / steps));
  return out;
}

SurfacePass lift_onto_cap(const EllipsoidCap& cap, const StrategyPolyline& xy, bool link, bool joined) {
  SurfacePass pass;
  pass.link = link;
  pass.joined = joined;
  pass.points.reserve(xy.size());
  for (const Eigen::Vector2d& p : xy) {
    const Eigen::Vector3d on_surface = cap_point_mm(cap, p);
    pass.points.push_back({on_surface, ellipsoid_normal(cap, on_surface)});
  }
  return pass;
}

// The outline scaled by `scale` at parametric angle phi.
Eigen::Vector2d scaled_outline_point(const StrategyLayout& g, double scale, double phi) {
  return {scale * g.outline_x_mm * std::cos(phi), scale * g.outline_y_mm * std::sin(phi)};
}

// The point `inset` inside the ellipse (major semi-axis `major` along x, minor along y) on the inward normal
// of its point at parametric angle phi. Past the smallest radius of curvature minor²/major the offset curve
// folds over itself near the major vertices; the points that fold across the major axis are not `inset` from
// the ellipse any more (a nearer point lies on the other side) and are replaced by the fold's corner on the
// axis.
Eigen::Vector2d inset_point_major_x(double major, double minor, double inset, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  const double root = std::sqrt(minor * minor * c * c + major * major * s * s);
  if (root * minor >= inset * major)
    return {c * (major - inset * minor / root), s * (minor - inset * major / root)};
  // The corner: where the folding starts, sin²φc = ((inset·major/minor)² − minor²) / (major² − minor²).
  const double ratio = inset * major / minor;
  const double sine_squared = (ratio * ratio - minor * minor) / (major * major - minor * minor);
  const double corner_cosine = std::sqrt(std::max(0.0, 1.0 - sine_squared));
  return {std::copysign(corner_cosine * (major - minor * minor / major), c), 0.0};
}

Eigen::Vector2d inset_outline_point(const StrategyLayout& g, double inset, double phi) {
  if (g.outline_x_mm >= g.outline_y_mm)
    return inset_point_major_x(g.outline_x_mm, g.outline_y_mm, inset, phi);
  // The longer axis along y: the same construction with the axes swapped (x ↔ y maps φ to π/2 − φ).
  const Eigen::Vector2d swapped =
      inset_point_major_x(g.outline_y_mm, g.outline_x_mm, inset, std::numbers::pi / 2 - phi);
  return {swapped.y(), swapped.x()};
}

// A closed loop (φ from 0 to 2π, counter-clockwise seen from above) of `at(φ)`.
template <class PointAt>
StrategyPolyline loop_points(const StrategyLayout& g, const PointAt& at) {
  return curve_points(at, 0.0, kStrategyTwoPi, g.dense_samples, g.point_gap_mm);
}

// Appends a loop, after a link from the previous piece's last point when there is one.
void append_linked(SurfaceToolPath& path, const StrategyLayout& g, const StrategyPolyline& loop) {
  if (!path.pieces.empty()) {
    const Eigen::Vector3d& last = path.pieces.back().points.back().position_mm;
    const Eigen::Vector2d from = (last - g.cap.centre_mm).head<2>();
    const StrategyPolyline link = straight_points(from, loop.front(), g.point_gap_mm, false);
    if (!link.empty()) path.pieces.push_back(lift_onto_cap(g.cap, link, true, true));
  }
  path.pieces.push_back(lift_onto_cap(g.cap, loop, false, !path.pieces.empty()));
}

void zigzag_passes(SurfaceToolPath& path, const StrategyLayout& g) {
  const double height = 2.0 * g.outline_y_mm;
  const int lines = std::max(1, static_cast<int>(std::ceil(height / g.pass_gap_mm)));
  const double gap = height / lines;
  for (int k = 0; k < lines; ++k) {
    const double y = -g.outline_y_mm + (k + 0.5) * gap;
    const double half =
        g.outline_x_mm * std::sqrt(std::max(0.0, 1.0 - (y / g.outline_y_mm) * (y / g.outline_y_mm)));
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    append_linked(path, g, straight_points({-sign * half, y}, {sign * half, y}, g.point_gap_mm, true));
  }
}

void meridian_passes(SurfaceToolPath& path, const StrategyLayout& g) {
  // Rim points at equal arc length, an even number of them so that every one has its opposite (φ + π lies
  // half the perimeter on by the outline's central symmetry); each pass runs from one through the pole to the
  // opposite one, and the next starts beside where it ended.
  StrategyPolyline rim;
  rim.reserve(static_cast<std::size_t>(g.dense_samples) + 1);
  for (int i = 0; i <= g.dense_samples; ++i)
    rim.push_back(scaled_outline_point(g, 1.0, kStrategyTwoPi * i / g.dense_samples));
  std::vector<double> along(rim.size(), 0.0);
  for (std::size_t i = 1; i < rim.size(); ++i) along[i] = along[i - 1] + (rim[i] - rim[i - 1]).norm();
  const double perimeter = along.back();
  const int meridians = 2 * std::max(1, static_cast<int>(std::ceil(perimeter / (2.0 * g.pass_gap_mm))));
  auto angle_at = [&](double length) {  // the parametric angle of the rim point `length` along it
    const auto it = std::lower_bound(along.begin(), along.end(), length);
    const std::size_t i =
        std::clamp<std::size_t>(static_cast<std::size_t>(it - along.begin()), 1, along.size() - 1);
    const double piece = along[i] - along[i - 1];
    const double t = piece > 0.0 ? (length - along[i - 1]) / piece : 0.0;
    return kStrategyTwoPi * (static_cast<double>(i - 1) + t) / g.dense_samples;
  };
  double previous_end = 0.0;
  for (int j = 0; j < meridians / 2; ++j) {
    const double phi = angle_at(perimeter * j / meridians);
    const double start = j % 2 == 0 ? phi : phi + std::numbers::pi;
    const double end = start + std::numbers::pi;
    if (j > 0) {  // along the rim from the last pass's end to this one's start, the short way round
      const double turn = std::remainder(start - previous_end, kStrategyTwoPi);
      StrategyPolyline link =
          curve_points([&](double t) { return scaled_outline_point(g, 1.0, t); }, previous_end,
                       previous_end + turn, std::max(2, g.dense_samples / meridians), g.point_gap_mm);
      link.erase(link.begin());
      link.pop_back();
      if (!link.empty()) path.pieces.push_back(lift_onto_cap(g.cap, link, true, true));
    }
    const StrategyPolyline diameter = straight_points(
        scaled_outline_point(g, 1.0, start), scaled_outline_point(g, 1.0, end), g.point_gap_mm, true);
    path.pieces.push_back(lift_onto_cap(g.cap, diameter, false, j > 0));
    previous_end = end;
  }
}

void parallel_passes(SurfaceToolPath& path, const StrategyLayout& g) {
  // Scaled outlines: the distance between two of them is at most the larger semi-axis times the scale step.
  const int loops =
      std::max(1, static_cast<int>(std::ceil(std::max(g.outline_x_mm, g.outline_y_mm) / g.pass_gap_mm)));
  for (int k = 0; k < loops; ++k) {
    const double scale = 1.0 - (k + 0.5) / loops;
    append_linked(path, g, loop_points(g, [&](double phi) { return scaled_outline_point(g, scale, phi); }));
  }
}

// Offsets δ_k = (k + ½)·d' inside the outline, d' = inradius / n ≤ d: every point of the outline's inside is
// within d'/2 of one of them (the distance to the outline changes at most as fast as one moves).
int contour_count(const StrategyLayout& g) {
  return std::max(1, static_cast<int>(std::ceil(std::min(g.outline_x_mm, g.outline_y_mm) / g.pass_gap_mm)));
}

void contour_passes(SurfaceToolPath& path, const StrategyLayout& g) {
  const int loops = contour_count(g);
  const double gap = std::min(g.outline_x_mm, g.outline_y_mm) / loops;
  for (int k = 0; k < loops; ++k) {
    const double inset = (k + 0.5) * gap;
    append_linked(path, g, loop_points(g, [&](double phi) { return inset_outline_point(g, inset, phi); }));
  }
}

void contour_loop_passes(SurfaceToolPath& path, const StrategyLayout& g) {
  const int loops = contour_count(g);
  const double gap = std::min(g.outline_x_mm, g.outline_y_mm) / loops;
  // Turn 0 at the first offset, turns 1 … n − 1 moving in by d' each, the last turn at the last offset.
  for (int turn = 0; turn <= loops; ++turn) {
    if (turn == loops && loops == 1) break;  // one offset: a single loop, no spiral
    const double first = 0.5 * gap + std::clamp(turn - 1, 0, loops - 1) * gap;
    const double rise = (turn == 0 || turn == loops) ? 0.0 : gap;
    StrategyPolyline turn_points = loop_points(
        g, [&](double phi) { return inset_outline_point(g, first + rise * phi / kStrategyTwoPi, phi); });
    if (turn > 0) turn_points.erase(turn_points.begin());  // the previous turn ended there
    path.pieces.push_back(lift_onto_cap(g.cap, turn_points, false, turn > 0));
  }
}

}  // namespace

std::string_view strategy_name(SurfaceStrategy strategy) {
  switch (strategy) {
    case SurfaceStrategy::zigzag:
      return "zigzag";
    case SurfaceStrategy::meridians:
      return "meridians";
    case SurfaceStrategy::parallels:
      return "parallels";
    case SurfaceStrategy::contour:
      return "contour";
    case SurfaceStrategy::contour_loop:
      return "contour_loop";
  }
  return "?";
}

std::size_t SurfaceToolPath::point_count() const {
  std::size_t n = 0;
  for (const SurfacePass& piece : pieces) n += piece.points.size();
  return n;
}

Status validate_strategy_options(const EllipsoidCap& cap, const StrategyOptions& options,
                                 std::size_t max_points) {
  if (Status valid = validate_ellipsoid_cap(cap); !valid) return valid;
  if (!std::isfinite(options.step_over_mm) || options.step_over_mm <= 0.0) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("step-over must be a positive length in mm, got {}", options.step_over_mm));
  }
  if (!std::isfinite(options.spacing_mm) || options.spacing_mm <= 0.0) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("point spacing must be a positive length in mm, got {}", options.spacing_mm));
  }
  // The meridians have the most points: about 2π·M²/(d·p) for the longer outline semi-axis M.
  const StrategyLayout g = strategy_layout(cap, options);
  const double longer = std::max(g.outline_x_mm, g.outline_y_mm);
  const double estimate = 4.0 * std::numbers::pi * longer * (longer / g.pass_gap_mm + 1.0) / g.point_gap_mm;
  if (estimate > static_cast<double>(max_points)) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("step-over {} mm and spacing {} mm on a {:.1f} × {:.1f} mm cap would need about "
                    "{:.3g} points (at most {}): choose a larger step-over or spacing",
                    options.step_over_mm, options.spacing_mm, 2 * g.outline_x_mm, 2 * g.outline_y_mm,
                    estimate, max_points));
  }
  return ok_status();
}

Result<SurfaceToolPath> generate_strategy(SurfaceStrategy strategy, const EllipsoidCap& cap,
                                          const StrategyOptions& options) {
  if (Status valid = validate_strategy_options(cap, options); !valid) return valid.error();
  const StrategyLayout g = strategy_layout(cap, options);
  SurfaceToolPath path;
  path.strategy = strategy;
  switch (strategy) {
    case SurfaceStrategy::zigzag:
      zigzag_passes(path, g);
      break;
    case SurfaceStrategy::meridians:
      meridian_passes(path, g);
      break;
    case SurfaceStrategy::parallels:
      parallel_passes(path, g);
      break;
    case SurfaceStrategy::contour:
      contour_passes(path, g);
      break;
    case SurfaceStrategy::contour_loop:
      contour_loop_passes(path, g);
      break;
  }
  return path;
}

}  // namespace pkm::path
