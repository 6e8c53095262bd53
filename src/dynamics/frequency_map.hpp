#pragma once
// A map of the machine's dynamic stiffness: the lowest natural frequency at each pose of a grid
// (pose_grid.hpp), with the reason where there is none. The poses are held to what `pkm modes --pose` asks
// of a single pose: the drives must reach it within the machine's actuator range, and the clamped machine
// must have a stable equilibrium there (natural_modes).
#include <limits>
#include <vector>

#include "dynamics/natural_frequencies.hpp"
#include "machine/machine.hpp"

namespace pkm::dynamics {

/// Why a map point has a frequency or not.
enum class MapPointStatus {
  ok,            ///< the lowest frequency is there
  unreachable,   ///< no actuator values reach the pose
  out_of_range,  ///< the actuators would leave the machine's range (actuator_min / actuator_max)
  singular,      ///< singular, unstable (ω² ≤ 0) or no static equilibrium found
};

/// "ok", "unreachable", "out_of_range", "singular": the words the map's CSV uses.
const char* to_string(MapPointStatus status);

struct FrequencyMapPoint {
  double lowest_frequency_Hz = std::numeric_limits<double>::quiet_NaN();  ///< NaN unless status is ok
  MapPointStatus status = MapPointStatus::singular;
};

/// The lowest natural frequency at each pose, or why there is none. `machine` is the one `model` was made
/// from: its actuator range decides out_of_range.
std::vector<FrequencyMapPoint> frequency_map(const Machine& machine, const ElasticModel& model,
                                             const std::vector<Pose>& poses,
                                             const ModalOptions& options = {});

struct FrequencyMapSummary {
  int points = 0;
  int with_frequency = 0;
  int unreachable = 0;
  int out_of_range = 0;
  int singular = 0;
  int lowest_index = -1;  ///< the point of the lowest frequency (the first of equals); -1 when none has one
  int highest_index = -1;
};

FrequencyMapSummary summarise_frequency_map(const std::vector<FrequencyMapPoint>& points);

}  // namespace pkm::dynamics
