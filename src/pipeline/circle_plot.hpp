#pragma once
// The circle test's polar plot (circle_test.hpp) as a standalone SVG: the nominal circle, each direction's
// radial deviation magnified about it, the magnification's scale ring and the figures G and H.
#include <string>

namespace pkm::pipeline {

struct CircleTestResult;

/// The plot of `result` for a circle of `radius_mm` in `plane` (XY, ZX or YZ).
std::string circle_plot_svg(const CircleTestResult& result, double radius_mm, const std::string& plane);

}  // namespace pkm::pipeline
