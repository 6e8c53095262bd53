#pragma once
// What a map over a grid of poses found (the lowest natural frequency, the weakest stiffness): how many
// points have a value, why the others have none, and where the lowest and the highest values are.
#include <vector>

namespace pkm::dynamics {

/// Why a map point has a value (a frequency, a stiffness) or not.
enum class MapPointStatus {
  ok,            ///< the value is there
  unreachable,   ///< no actuator values reach the pose
  out_of_range,  ///< the actuators would leave the machine's range (actuator_min / actuator_max)
  singular,      ///< singular, unstable (ω² ≤ 0) or no static equilibrium found
};

/// "ok", "unreachable", "out_of_range", "singular": the words the map's CSV uses.
const char* to_string(MapPointStatus status);

struct MapPointCounts {
  int points = 0;
  int with_value = 0;
  int unreachable = 0;
  int out_of_range = 0;
  int singular = 0;
  int lowest_index = -1;  ///< the first of equals; -1 when no point has a value
  int highest_index = -1;
};

/// `value(point)` is read at the points whose status is ok.
template <class Point, class Value>
MapPointCounts count_map_points(const std::vector<Point>& points, Value value) {
  MapPointCounts c;
  c.points = static_cast<int>(points.size());
  for (int i = 0; i < c.points; ++i) {
    switch (points[i].status) {
      case MapPointStatus::ok:
        ++c.with_value;
        if (c.lowest_index < 0 || value(points[i]) < value(points[c.lowest_index])) c.lowest_index = i;
        if (c.highest_index < 0 || value(points[i]) > value(points[c.highest_index])) c.highest_index = i;
        break;
      case MapPointStatus::unreachable:
        ++c.unreachable;
        break;
      case MapPointStatus::out_of_range:
        ++c.out_of_range;
        break;
      case MapPointStatus::singular:
        ++c.singular;
        break;
    }
  }
  return c;
}

}  // namespace pkm::dynamics
