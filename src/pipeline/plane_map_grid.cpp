#include "pipeline/plane_map_grid.hpp"

#include <fmt/format.h>

namespace pkm::pipeline {

Result<PlaneMapGrid> plane_map_grid(const Mechanism& mechanism, const dynamics::PlaneGrid& grid) {
  if (mechanism.is_planar() && grid.plane != dynamics::GridPlane::xy) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("plane {}: a planar machine moves in the xy plane only",
                                  dynamics::to_string(grid.plane)));
  }
  auto poses = dynamics::plane_grid_poses(grid, kMaxMapGridPoints);
  if (!poses) return poses.error();
  return PlaneMapGrid{dynamics::grid_points_per_axis(grid.half_range_mm, grid.step_mm), std::move(*poses)};
}

}  // namespace pkm::pipeline
