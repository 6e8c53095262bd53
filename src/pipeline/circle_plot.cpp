#include "pipeline/circle_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pipeline/circle_test.hpp"

namespace pkm::pipeline {

namespace {

constexpr double kSize = 600.0;                 // px, square
constexpr double kNominal = 0.6 * kSize / 2.0;  // px: the nominal circle's radius
constexpr double kBand = 0.3 * kSize / 2.0;     // px: the largest deviation drawn this far from it

// One direction's trace as a closed polyline, its deviation magnified `scale` px per mm.
std::string trace_path(const CircleTrace& trace, double scale, const char* colour) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < trace.angle_deg.size(); ++i)
    points.emplace_back(trace.angle_deg[i], trace.deviation_mm[i]);
  std::sort(points.begin(), points.end());
  std::string d;
  for (const auto& [angle, deviation] : points) {
    const double r = kNominal + deviation * scale;
    const double a = angle * std::numbers::pi / 180.0;
    d += fmt::format("{}{:.2f},{:.2f}", d.empty() ? "M" : " L", kSize / 2.0 + r * std::cos(a),
                     kSize / 2.0 - r * std::sin(a));
  }
  return fmt::format("<path d=\"{} Z\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.2\"/>\n", d, colour);
}

// A round number of µm per ring near `span_um`.
double ring_step_um(double span_um) {
  const double raw = std::max(span_um, 1e-3);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= raw) return m * decade;
  return 10.0 * decade;
}

}  // namespace

std::string circle_plot_svg(const CircleTestResult& result, double radius_mm, const std::string& plane) {
  double largest = 1e-9;
  for (const CircleTrace* t : {&result.counter_clockwise, &result.clockwise})
    for (double d : t->deviation_mm) largest = std::max(largest, std::abs(d));
  const double ring_um = ring_step_um(largest * 1e3);
  const double scale = kBand / (ring_um * 1e-3);  // px per mm of deviation
  const double c = kSize / 2.0;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{0}\" viewBox=\"0 0 {0} {0}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{0}\" fill=\"white\"/>\n",
      kSize);
  // The nominal circle and the rings one scale step inside and outside it.
  for (int k = -1; k <= 1; ++k) {
    svg += fmt::format(
        "<circle cx=\"{0}\" cy=\"{0}\" r=\"{1:.2f}\" fill=\"none\" stroke=\"{2}\" "
        "stroke-dasharray=\"{3}\"/>\n",
        c, kNominal + k * kBand, k == 0 ? "#888" : "#ccc", k == 0 ? "none" : "4 3");
  }
  svg +=
      fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#eee\"/>\n", c, 10, kSize - 10);
  svg +=
      fmt::format("<line x1=\"{1}\" y1=\"{0}\" x2=\"{2}\" y2=\"{0}\" stroke=\"#eee\"/>\n", c, 10, kSize - 10);
  svg += trace_path(result.counter_clockwise, scale, "#1f77b4");
  svg += trace_path(result.clockwise, scale, "#d62728");
  svg += fmt::format(
      "<text x=\"10\" y=\"20\">circle test, R {:g} mm in {}: one ring = {:g} µm of radial deviation</text>\n"
      "<text x=\"10\" y=\"38\" fill=\"#1f77b4\">G3 (counter-clockwise): G = {:.2f} µm</text>\n"
      "<text x=\"10\" y=\"56\" fill=\"#d62728\">G2 (clockwise): G = {:.2f} µm</text>\n"
      "<text x=\"10\" y=\"74\">hysteresis H = {:.2f} µm</text>\n</svg>\n",
      radius_mm, plane, ring_um, result.counter_clockwise.circular_deviation_mm * 1e3,
      result.clockwise.circular_deviation_mm * 1e3, result.hysteresis_mm * 1e3);
  return svg;
}

}  // namespace pkm::pipeline
