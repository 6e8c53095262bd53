// All assembly modes of a glide machine at given carriage positions (machine/carriage_assembly_modes.hpp):
// the hexaglide's are those of the Gough–Stewart platform its carriage joints make, the triglide's the two
// points of its three struts' spheres.
#include <fmt/format.h>

#include <cmath>

#include "machine/carriage_assembly_modes.hpp"
#include "machine/glide.hpp"

namespace pkm {

Result<AssemblyModes> Glide::assembly_modes(const ActuatorVector& q, const FkOptions& options) const {
  const int n = geometry_.count;
  if (q.size() != n)
    return make_error(ErrorCode::bad_input,
                      fmt::format("a glide machine of {} guides needs {} carriage positions", n, n));
  for (int j = 0; j < n; ++j) {
    if (!std::isfinite(q[j]))
      return make_error(ErrorCode::bad_input,
                        fmt::format("carriage {} position {} is not a number", j + 1, q[j]));
  }
  if (n == 3) {
    std::array<Eigen::Vector3d, 3> carriages, platform;
    std::array<double, 3> lengths{};
    for (int j = 0; j < 3; ++j) {
      carriages[j] = carriage_mm(j, q[j]);
      platform[j] = geometry_.platform_joints_mm[j];
      lengths[j] = geometry_.strut_lengths_mm[j];
    }
    return three_carriage_assembly_modes(*this, q, carriages, platform, lengths, Eigen::Matrix3d::Identity());
  }
  std::array<Eigen::Vector3d, 6> carriages;
  for (int j = 0; j < 6; ++j) carriages[j] = carriage_mm(j, q[j]);
  return carriage_assembly_modes(*this, q, carriages, geometry_.platform_joints_mm,
                                 geometry_.strut_lengths_mm, options,
                                 [this](const Pose& pose) { return assembly_mode(pose) == home_mode_; });
}

Result<std::vector<FkSolution>> Glide::forward_all(const ActuatorVector& q, const FkOptions& options) const {
  auto modes = assembly_modes(q, options);
  if (!modes) return modes.error();
  return std::move(modes->solutions);
}

}  // namespace pkm
