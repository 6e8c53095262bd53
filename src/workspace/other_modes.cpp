#include "workspace/other_modes.hpp"

#include <cmath>

#include "core/units.hpp"

namespace pkm::workspace {

OtherAssemblyModes other_assembly_modes(const Mechanism& mechanism, const Pose& pose,
                                        const ActuatorVector& actuators, double same_mode_mm) {
  OtherAssemblyModes out;
  auto all = mechanism.forward_all(actuators);
  if (!all) {
    out.note = all.error().message;
    return out;
  }
  out.enumerated = true;
  out.real_modes = static_cast<int>(all->size());
  const double length_mm = mechanism.platform_size_mm();
  // X0's own mode is the solution nearest X0; every other one is another mode.
  int own = -1;
  double own_distance_mm = INFINITY;
  std::vector<PoseDistance> distances;
  distances.reserve(all->size());
  for (std::size_t i = 0; i < all->size(); ++i) {
    const PoseDistance d = pose_distance(pose, (*all)[i].pose);
    distances.push_back(d);
    const double combined_mm = d.position_mm + length_mm * d.rotation_rad;
    if (combined_mm < own_distance_mm) {
      own_distance_mm = combined_mm;
      own = static_cast<int>(i);
    }
  }
  out.current_found = own >= 0 && own_distance_mm <= same_mode_mm;
  if (!out.current_found) {
    out.note = "the pose's own assembly mode was not among the modes forward kinematics enumerated";
    own = -1;  // then every enumerated mode counts as another one
  }
  for (std::size_t i = 0; i < all->size(); ++i) {
    if (static_cast<int>(i) == own) continue;
    const double combined_mm = distances[i].position_mm + length_mm * distances[i].rotation_rad;
    if (std::isnan(out.nearest_other_distance_mm) || combined_mm < out.nearest_other_distance_mm) {
      out.nearest_other_distance_mm = combined_mm;
      out.nearest_other_position_mm = distances[i].position_mm;
      out.nearest_other_rotation_deg = deg_from_rad(distances[i].rotation_rad);
      out.nearest_other = (*all)[i].pose;
    }
  }
  return out;
}

}  // namespace pkm::workspace
