#include "formats/frequency_map_csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dynamics/pose_grid_columns.hpp"

namespace pkm::formats {

std::string frequency_map_csv(const Mechanism& mechanism, const std::vector<Pose>& poses,
                              const std::vector<dynamics::FrequencyMapPoint>& points) {
  std::string csv =
      fmt::format("{},lowest_frequency_Hz,status\n", fmt::join(dynamics::grid_pose_columns(mechanism), ","));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    csv += dynamics::grid_pose_cells(mechanism, poses[i]);
    if (points[i].status == dynamics::MapPointStatus::ok)
      csv += fmt::format("{:.6f}", points[i].lowest_frequency_Hz);
    csv += fmt::format(",{}\n", dynamics::to_string(points[i].status));
  }
  return csv;
}

}  // namespace pkm::formats
