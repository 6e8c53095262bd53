#include "pipeline/simulate_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pipeline/simulate_program.hpp"

namespace pkm::pipeline {

namespace {

constexpr double kWidth = 800.0, kPanel = 300.0, kMargin = 50.0;  // px
constexpr std::size_t kSlices = 400;                              // of the error along the program

// The error panel: the largest error in each slice of the ticks, as a polyline.
std::string error_panel(const servo::ServoRunInput& input, const std::vector<Eigen::Vector3d>& contour_mm,
                        const SimulateResult& result, double top) {
  const std::size_t ticks = input.time_s.size();
  const double largest = std::max(result.total.max_mm, 1e-9);
  const double t0 = input.time_s.front(), span = std::max(input.time_s.back() - t0, 1e-9);
  const double plot_w = kWidth - 2 * kMargin, plot_h = kPanel - 2 * kMargin;
  std::string d;
  const std::size_t slices = std::min(kSlices, ticks);
  for (std::size_t s = 0; s < slices; ++s) {
    const std::size_t from = s * ticks / slices, to = std::max(from + 1, (s + 1) * ticks / slices);
    double worst = 0.0;
    for (std::size_t k = from; k < to; ++k) {
      const double e = contour_mm[k].norm();
      if (std::isfinite(e)) worst = std::max(worst, e);
    }
    const double x = kMargin + plot_w * (input.time_s[from] - t0) / span;
    const double y = top + kMargin + plot_h * (1.0 - worst / largest);
    d += fmt::format("{}{:.1f},{:.1f}", d.empty() ? "M" : " L", x, y);
  }
  std::string svg = fmt::format(
      "<rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{3}\" fill=\"none\" stroke=\"#ccc\"/>\n"
      "<path d=\"{4}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.2\"/>\n"
      "<text x=\"{0}\" y=\"{5}\">contour error along the program: 0 … {6:.2f} µm over {7:.2f} s; largest at "
      "line "
      "{8} (t = {9:.3f} s)</text>\n",
      kMargin, top + kMargin, plot_w, plot_h, d, top + kMargin - 8, largest * 1e3, span,
      result.total.max_line, result.total.max_time_s);
  const double x_max = kMargin + plot_w * (result.total.max_time_s - t0) / span;
  svg += fmt::format(
      "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#888\" "
      "stroke-dasharray=\"4 3\"/>\n",
      x_max, top + kMargin, top + kMargin + plot_h);
  return svg;
}

// The path panel: commanded and actual tool points seen from above, the actual ones at the commanded point
// plus `magnify` times the error vector.
std::string path_panel(const servo::ServoRunInput& input, const std::vector<Eigen::Vector3d>& contour_mm,
                       const SimulateResult& result, double top) {
  const std::size_t ticks = input.time_s.size();
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300), high = Eigen::Vector2d::Constant(-1e300);
  for (const Pose& p : input.pose) {
    low = low.cwiseMin(p.position_mm.head<2>());
    high = high.cwiseMax(p.position_mm.head<2>());
  }
  const double size = std::max((high - low).maxCoeff(), 1e-6);
  const double plot = kPanel * 2 - 2 * kMargin;
  const double scale = plot / size;  // px per mm
  // The error drawn as a twentieth of the path's size at its largest.
  const double magnify = result.total.max_mm > 0.0 ? 0.05 * size / result.total.max_mm : 1.0;
  const std::size_t stride = std::max<std::size_t>(1, ticks / 4000);
  std::string commanded, actual;
  for (std::size_t k = 0; k < ticks; k += stride) {
    const Eigen::Vector3d c = input.pose[k].position_mm;
    Eigen::Vector3d a = c + magnify * contour_mm[k];
    if (!a.allFinite()) a = c;
    const auto xy = [&](const Eigen::Vector3d& p) {
      return std::pair{kMargin + (p.x() - low.x()) * scale, top + kMargin + (high.y() - p.y()) * scale};
    };
    const auto [cx, cy] = xy(c);
    const auto [ax, ay] = xy(a);
    commanded += fmt::format("{}{:.1f},{:.1f}", commanded.empty() ? "M" : " L", cx, cy);
    actual += fmt::format("{}{:.1f},{:.1f}", actual.empty() ? "M" : " L", ax, ay);
  }
  return fmt::format(
      "<text x=\"{0}\" y=\"{1}\">tool path from above (X right, Y up): commanded (grey) and actual (blue), "
      "the "
      "error magnified {2:.3g}×</text>\n"
      "<path d=\"{3}\" fill=\"none\" stroke=\"#999\" stroke-width=\"1\"/>\n"
      "<path d=\"{4}\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1\"/>\n",
      kMargin, top + kMargin - 8, magnify, commanded, actual);
}

}  // namespace

std::string simulate_plot_svg(const servo::ServoRunInput& input,
                              const std::vector<Eigen::Vector3d>& contour_mm, const SimulateResult& result) {
  const double height = 3 * kPanel;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      kWidth, height);
  if (!input.time_s.empty()) {
    svg += error_panel(input, contour_mm, result, 0.0);
    svg += path_panel(input, contour_mm, result, kPanel);
  }
  return svg + "</svg>\n";
}

}  // namespace pkm::pipeline
