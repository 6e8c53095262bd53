#pragma once
// The pose columns of a map's CSV over a grid of poses (pose_grid.hpp): the numbers `--pose` takes, so a
// row can be pasted back into `pkm modes --pose` or `pkm compliance --pose`. Shared by the maps of the
// lowest natural frequency (`pkm modes --map`) and of the lowest stiffness (stiffness/stiffness_map.hpp).
#include <string>
#include <vector>

#include "machine/mechanism.hpp"

namespace pkm::dynamics {

/// x_mm, y_mm, z_mm and the angles in degrees, named in the machine's convention (a1_deg …); planar
/// machines their controlled coordinates only (as user_from_pose gives them).
std::vector<std::string> grid_pose_columns(const Mechanism& mechanism);

/// The pose's cells in those columns, each followed by a comma ("10.000000,-20.000000,…,").
std::string grid_pose_cells(const Mechanism& mechanism, const Pose& pose);

}  // namespace pkm::dynamics
