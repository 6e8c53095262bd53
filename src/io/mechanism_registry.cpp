#include <cmath>

#include "io/mechanism_files.hpp"

namespace pkm {

const std::vector<MechanismFileEntry>& mechanism_file_entries() {
  static const std::vector<MechanismFileEntry> entries = {
      planar2_file_entry(), planar3_file_entry(),         hexapod_file_entry(), tripod_file_entry(),
      tricept_file_entry(), hexapod_refined_file_entry(), glide_file_entry(),   rotopod_file_entry(),
  };
  return entries;
}

double default_home_height_mm(const std::vector<Eigen::Vector3d>& base_joints_mm,
                              const std::vector<Eigen::Vector3d>& platform_joints_tool_mm,
                              const ActuatorLimits& limits) {
  const std::size_t n = std::min(base_joints_mm.size(), platform_joints_tool_mm.size());
  double base_radius = 0.0;
  for (const auto& a : base_joints_mm)
    base_radius += a.head<2>().norm() / static_cast<double>(base_joints_mm.size());
  const double length = (limits.min && limits.max) ? 0.5 * (*limits.min + *limits.max) : 1.2 * base_radius;
  double height = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double horizontal = (platform_joints_tool_mm[j].head<2>() - base_joints_mm[j].head<2>()).norm();
    const double vertical = std::sqrt(std::fmax(length * length - horizontal * horizontal, 1.0));
    height += (vertical + base_joints_mm[j].z() - platform_joints_tool_mm[j].z()) / static_cast<double>(n);
  }
  return height;
}

}  // namespace pkm
