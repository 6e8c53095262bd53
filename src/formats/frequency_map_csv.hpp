#pragma once
// The CSV of `pkm modes --map`: the lowest natural frequency over a grid of poses.
#include <string>
#include <vector>

#include "dynamics/frequency_map.hpp"

namespace pkm::formats {

/// The pose columns of `--pose` (dynamics/pose_grid_columns.hpp), lowest_frequency_Hz (empty where the point
/// has none) and status ("ok", "unreachable", "out_of_range", "singular"); one row per grid point.
std::string frequency_map_csv(const Mechanism& mechanism, const std::vector<Pose>& poses,
                              const std::vector<dynamics::FrequencyMapPoint>& points);

}  // namespace pkm::formats
