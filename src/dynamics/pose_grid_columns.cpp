#include "dynamics/pose_grid_columns.hpp"

#include <fmt/format.h>

#include "io/pose_input.hpp"

namespace pkm::dynamics {

std::vector<std::string> grid_pose_columns(const Mechanism& mechanism) {
  const auto names = pose_coordinate_names(mechanism);
  const AxisMask mask = mechanism.controlled_axes();
  std::vector<std::string> columns;
  for (int i = 0; i < 6; ++i) {
    if (mechanism.is_planar() && !mask.controlled[i]) continue;  // as user_from_pose
    columns.push_back(names[i] + (i < 3 ? "_mm" : "_deg"));
  }
  return columns;
}

std::string grid_pose_cells(const Mechanism& mechanism, const Pose& pose) {
  std::string cells;
  for (double v : user_from_pose(mechanism, pose)) cells += fmt::format("{:.6f},", v);
  return cells;
}

}  // namespace pkm::dynamics
