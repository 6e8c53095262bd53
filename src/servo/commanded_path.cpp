#include "servo/commanded_path.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::servo {

Eigen::Vector3d controlled_point(const Eigen::Vector3d& point, const AxisMask& axes) {
  Eigen::Vector3d out = point;
  for (int c = 0; c < 3; ++c) {
    if (!axes.controlled[c]) out[c] = 0.0;
  }
  return out;
}

CommandedPath commanded_path(const ServoRunInput& input, const AxisMask& axes) {
  const std::size_t ticks = input.time_s.size();
  std::vector<Eigen::Vector3d> tick_points(ticks);
  for (std::size_t k = 0; k < ticks; ++k) tick_points[k] = controlled_point(input.pose[k].position_mm, axes);
  CommandedPath path{std::vector<Eigen::Vector3d>(2 * ticks - 1), std::vector<double>(2 * ticks - 1),
                     std::vector<double>(ticks, 0.0), 0.0};
  for (std::size_t k = 0; k < ticks; ++k) {
    path.points[2 * k] = tick_points[k];
    path.time_s[2 * k] = input.time_s[k];
    if (k + 1 == ticks) break;
    const Eigen::Vector3d& before = tick_points[k > 0 ? k - 1 : k];
    const Eigen::Vector3d& after = tick_points[k + 2 < ticks ? k + 2 : k + 1];
    path.points[2 * k + 1] = (9.0 * (tick_points[k] + tick_points[k + 1]) - before - after) / 16.0;
    path.time_s[2 * k + 1] = 0.5 * (input.time_s[k] + input.time_s[k + 1]);
  }
  for (std::size_t k = 1; k + 1 < ticks; ++k) {
    path.speed[k] = (tick_points[k + 1] - tick_points[k - 1]).norm() / (2.0 * input.period_s);
    path.fastest = std::max(path.fastest, path.speed[k]);
  }
  return path;
}

NearestOnPath nearest_on_path(const CommandedPath& path, std::size_t first, std::size_t last,
                              const Eigen::Vector3d& point) {
  NearestOnPath best{(point - path.points[first]).norm(), path.time_s[first], path.points[first]};
  for (std::size_t j = first + 1; j <= last; ++j) {
    const Eigen::Vector3d a = path.points[j - 1], chord = path.points[j] - a;
    const double length2 = chord.squaredNorm();
    const double f = length2 > 0.0 ? std::clamp((point - a).dot(chord) / length2, 0.0, 1.0) : 0.0;
    const Eigen::Vector3d on = a + f * chord;
    const double d = (point - on).norm();
    if (d <= best.distance_mm) {
      best = {d, path.time_s[j - 1] + f * (path.time_s[j] - path.time_s[j - 1]), on};
    }
  }
  return best;
}

std::size_t search_window(const LoopDesign& design, const ServoRunInput& input) {
  double slowest_s = input.period_s;
  for (int j = 0; j < design.drives; ++j) {
    const ChannelGains& c = design.channels[j];
    const double loop_s = c.position_gain_per_s > 0.0 ? 1.0 / c.position_gain_per_s : 0.0;
    slowest_s = std::max(slowest_s, 4.0 * loop_s + 4.0 * c.lag_s + c.reference_filter_s);
  }
  return static_cast<std::size_t>(std::min(5000.0, std::ceil(slowest_s / input.period_s) + 2.0));
}

}  // namespace pkm::servo
