#pragma once
// A map of the machine's dynamic stiffness: the lowest natural frequency at each pose of a grid
// (pose_grid.hpp), with the reason where there is none. The poses are held to what `pkm modes --pose` asks
// of a single pose: the drives must reach it within the machine's actuator range, and the clamped machine
// must have a stable equilibrium there (natural_modes).
#include <limits>
#include <vector>

#include "dynamics/map_point_counts.hpp"
#include "dynamics/natural_frequencies.hpp"
#include "machine/machine.hpp"

namespace pkm::dynamics {

struct FrequencyMapPoint {
  double lowest_frequency_Hz = std::numeric_limits<double>::quiet_NaN();  ///< NaN unless status is ok
  MapPointStatus status = MapPointStatus::singular;
};

/// The lowest natural frequency at each pose, or why there is none. `machine` is the one `model` was made
/// from: its actuator range decides out_of_range.
std::vector<FrequencyMapPoint> frequency_map(const Machine& machine, const ElasticModel& model,
                                             const std::vector<Pose>& poses,
                                             const ModalOptions& options = {});

using FrequencyMapSummary = MapPointCounts;

FrequencyMapSummary summarise_frequency_map(const std::vector<FrequencyMapPoint>& points);

}  // namespace pkm::dynamics
