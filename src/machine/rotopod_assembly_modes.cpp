// All assembly modes of a rotopod at given carriage angles (machine/carriage_assembly_modes.hpp): those of
// the Gough–Stewart platform its carriage joints make on their circle.
#include <fmt/format.h>

#include <cmath>

#include "machine/carriage_assembly_modes.hpp"
#include "machine/rotopod.hpp"

namespace pkm {

Result<AssemblyModes> Rotopod::assembly_modes(const ActuatorVector& q, const FkOptions& options) const {
  if (q.size() != 6) return make_error(ErrorCode::bad_input, "a rotopod needs 6 carriage angles");
  std::array<Eigen::Vector3d, 6> carriages;
  for (int j = 0; j < 6; ++j) {
    if (!std::isfinite(q[j]))
      return make_error(ErrorCode::bad_input,
                        fmt::format("carriage {} angle {} is not a number", j + 1, q[j]));
    carriages[j] = carriage_mm(j, q[j]);
  }
  return carriage_assembly_modes(*this, q, carriages, geometry_.platform_joints_mm,
                                 geometry_.strut_lengths_mm, options,
                                 [this](const Pose& pose) { return assembly_mode(pose) == home_mode_; });
}

Result<std::vector<FkSolution>> Rotopod::forward_all(const ActuatorVector& q,
                                                     const FkOptions& options) const {
  auto modes = assembly_modes(q, options);
  if (!modes) return modes.error();
  return std::move(modes->solutions);
}

}  // namespace pkm
