#include "interpolation/error_amplification_scan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "machine/conditioning.hpp"

namespace pkm::interpolation {

ErrorAmplificationScan::ErrorAmplificationScan(const Machine& machine, double spacing, std::string source)
    : machine_(machine), spacing_(spacing), source_(std::move(source)) {}

Status ErrorAmplificationScan::measure(const path::PathPoint& point, int line) {
  auto measures =
      jacobian_measures(*machine_.mechanism, Pose{point.position_mm, point.rotation.toRotationMatrix()});
  if (!measures) {
    const std::string place = line > 0 ? fmt::format("{}:{}", source_, line) : source_;
    const std::string what = line > 0 ? " (δρ along the path)" : "";
    return Error{measures.error().code, fmt::format("{}: {}{}", place, measures.error().message, what)};
  }
  if (measures->error_amplification > result_.largest) {
    result_.largest = measures->error_amplification;
    result_.line = line;
  }
  sampled_ = true;
  return ok_status();
}

Status ErrorAmplificationScan::add_segment(const path::Path& path, int index) {
  const path::Segment& segment = path.segment(index);
  const int samples = std::max(1, static_cast<int>(std::ceil(segment.length / spacing_)));
  for (int k = 0; k <= samples; ++k) {
    const double s = segment.s_start + segment.length * k / samples;
    if (Status measured = measure(path.evaluate(s, hint_), segment.line); !measured) return measured;
  }
  return ok_status();
}

Status ErrorAmplificationScan::finish(const path::Path& path) {
  if (sampled_) return ok_status();
  return measure(path.start, 0);
}

}  // namespace pkm::interpolation
