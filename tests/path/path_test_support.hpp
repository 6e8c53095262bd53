#pragma once
// Test helpers for paths: the distance from a point to a programmed move, computed independently of the
// planner's own measure (corner_blend.cpp), so that blend tests do not check the code with itself.
#include <Eigen/Core>
#include <algorithm>

#include "path/curve.hpp"

namespace pkm::test {

/// Distance from `point` to the whole move `c`: exact for lines, else a dense scan refined by golden
/// sections.
inline double distance_to_programmed_move(const path::Curve& c, const Eigen::Vector3d& point) {
  if (c.kind == path::CurveKind::line && c.tool_length_mm == 0.0) {
    const Eigen::Vector3d d = c.end_mm - c.start_mm;
    const double t = std::clamp((point - c.start_mm).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    return (c.start_mm + t * d - point).norm();
  }
  constexpr int scan = 400;
  int best = 0;
  double best_distance = 1e300;
  for (int k = 0; k <= scan; ++k) {
    const double d = (c.position(static_cast<double>(k) / scan) - point).norm();
    if (d < best_distance) best_distance = d, best = k;
  }
  double lo = std::max(0.0, (best - 1.0) / scan), hi = std::min(1.0, (best + 1.0) / scan);
  for (int it = 0; it < 60; ++it) {
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    if ((c.position(m1) - point).norm() < (c.position(m2) - point).norm()) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return std::min(best_distance, (c.position(0.5 * (lo + hi)) - point).norm());
}

}  // namespace pkm::test
