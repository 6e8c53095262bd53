#include "formats/stiffness_csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dynamics/pose_grid_columns.hpp"
#include "io/output_file.hpp"

namespace pkm::formats {

std::string stiffness_map_csv(const Mechanism& mechanism, const std::vector<Pose>& poses,
                              const std::vector<stiffness::StiffnessMapPoint>& points) {
  std::string csv = fmt::format("{},lowest_stiffness_N_um,direction_x,direction_y,direction_z,status\n",
                                fmt::join(dynamics::grid_pose_columns(mechanism), ","));
  for (std::size_t i = 0; i < poses.size() && i < points.size(); ++i) {
    csv += dynamics::grid_pose_cells(mechanism, poses[i]);
    const stiffness::StiffnessMapPoint& p = points[i];
    if (p.status == dynamics::MapPointStatus::ok) {
      csv += fmt::format("{:.9g},{:.6f},{:.6f},{:.6f}", p.lowest_stiffness_N_um, p.direction.x(),
                         p.direction.y(), p.direction.z());
    } else {
      csv += ",,,";
    }
    csv += fmt::format(",{}\n", dynamics::to_string(p.status));
  }
  return csv;
}

Status write_stiffness_map_csv(const std::string& path, const Mechanism& mechanism,
                               const std::vector<Pose>& poses,
                               const std::vector<stiffness::StiffnessMapPoint>& points) {
  return write_output_file(path, stiffness_map_csv(mechanism, poses, points));
}

std::string bode_csv(const stiffness::BodeData& data) {
  std::string csv = "frequency_Hz";
  for (const stiffness::BodeEntry& e : data.entries)
    csv += fmt::format(",{0}_magnitude_um_N,{0}_phase_deg", e.name);
  csv += '\n';
  for (std::size_t k = 0; k < data.frequency_Hz.size(); ++k) {
    csv += fmt::format("{:.9g}", data.frequency_Hz[k]);
    for (std::size_t e = 0; e < data.entries.size(); ++e)
      csv += fmt::format(",{:.9g},{:.6f}", data.magnitude_um_N[e][k], data.phase_deg[e][k]);
    csv += '\n';
  }
  return csv;
}

Status write_bode_csv(const std::string& path, const stiffness::BodeData& data) {
  return write_output_file(path, bode_csv(data));
}

}  // namespace pkm::formats
