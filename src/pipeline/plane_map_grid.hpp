#pragma once
// The plane grid of poses the maps of `pkm modes --map` and `pkm compliance --map` are computed over
// (dynamics/pose_grid.hpp), held to what both jobs accept: a plane the machine moves in, and no more points
// than kMaxMapGridPoints.
#include <vector>

#include "dynamics/pose_grid.hpp"
#include "machine/mechanism.hpp"

namespace pkm::pipeline {

/// The most grid points a map may have: ~30 µs each on the ch5 hexapod (and ~80 bytes of CSV), so the cap
/// is about half a minute and 80 MB; more is almost always a mistyped step. `pkm workspace` takes the same
/// cap for its cells.
inline constexpr double kMaxMapGridPoints = 1'000'000;

struct PlaneMapGrid {
  double points_per_axis = 0.0;
  std::vector<Pose> poses;  ///< in the grid's order (dynamics::plane_grid_poses)
};

/// The poses of `grid` for `mechanism`. Refuses (bad_input) a plane other than xy for a planar machine,
/// naming `plane`, and a grid dynamics::plane_grid_poses refuses (a step that is no positive number, more
/// than kMaxMapGridPoints points).
Result<PlaneMapGrid> plane_map_grid(const Mechanism& mechanism, const dynamics::PlaneGrid& grid);

}  // namespace pkm::pipeline
