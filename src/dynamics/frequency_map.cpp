#include "dynamics/frequency_map.hpp"

#include <limits>

#include "dynamics/map_point_counts.hpp"

namespace pkm::dynamics {
namespace {

FrequencyMapPoint lowest_frequency_at(const Machine& machine, const ElasticModel& model, const Pose& pose,
                                      const ModalOptions& options) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // The range check comes first, as in `pkm modes --pose`: natural_modes knows the geometry, not the drives.
  auto actuators = machine.mechanism->inverse(pose);
  if (!actuators) return {kNone, MapPointStatus::unreachable};
  if (!check_actuator_range(machine, *actuators)) return {kNone, MapPointStatus::out_of_range};
  auto modes = natural_modes(model, pose, options);
  if (modes) return {modes->frequency_Hz[0], MapPointStatus::ok};
  switch (modes.error().code) {
    case ErrorCode::unreachable:
      return {kNone, MapPointStatus::unreachable};
    case ErrorCode::limit_exceeded:
      return {kNone, MapPointStatus::out_of_range};
    default:
      return {kNone, MapPointStatus::singular};
  }
}

}  // namespace

const char* to_string(MapPointStatus status) {
  switch (status) {
    case MapPointStatus::ok:
      return "ok";
    case MapPointStatus::unreachable:
      return "unreachable";
    case MapPointStatus::out_of_range:
      return "out_of_range";
    case MapPointStatus::singular:
      return "singular";
  }
  return "singular";
}

std::vector<FrequencyMapPoint> frequency_map(const Machine& machine, const ElasticModel& model,
                                             const std::vector<Pose>& poses, const ModalOptions& options) {
  std::vector<FrequencyMapPoint> points;
  points.reserve(poses.size());
  for (const Pose& pose : poses) points.push_back(lowest_frequency_at(machine, model, pose, options));
  return points;
}

FrequencyMapSummary summarise_frequency_map(const std::vector<FrequencyMapPoint>& points) {
  return dynamics::count_map_points(points, [](const FrequencyMapPoint& p) { return p.lowest_frequency_Hz; });
}

}  // namespace pkm::dynamics
