#include "dynamics/pose_grid.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::dynamics {

const char* to_string(GridPlane plane) {
  switch (plane) {
    case GridPlane::xy:
      return "xy";
    case GridPlane::xz:
      return "xz";
    case GridPlane::yz:
      return "yz";
  }
  return "xy";
}

Result<GridPlane> grid_plane_from_string(std::string_view name) {
  for (GridPlane plane : {GridPlane::xy, GridPlane::xz, GridPlane::yz}) {
    if (name == to_string(plane)) return plane;
  }
  return make_error(ErrorCode::bad_input, fmt::format("unknown plane '{}' (xy, xz or yz)", name));
}

std::array<int, 2> grid_plane_axes(GridPlane plane) {
  switch (plane) {
    case GridPlane::xy:
      return {0, 1};
    case GridPlane::xz:
      return {0, 2};
    case GridPlane::yz:
      return {1, 2};
  }
  return {0, 1};
}

double grid_points_per_axis(double half_range_mm, double step_mm) {
  // The tolerance keeps a range that is a whole number of steps in decimal (200 by 0.1) from losing its
  // last point to the binary rounding of the quotient (1999.9999999999998).
  const double steps = std::floor(half_range_mm / step_mm * (1.0 + 1e-9));
  return 2.0 * steps + 1.0;
}

Result<std::vector<Pose>> plane_grid_poses(const PlaneGrid& grid, double max_points) {
  if (!(std::isfinite(grid.step_mm) && grid.step_mm > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("grid step must be a positive number of mm, got {}", grid.step_mm));
  }
  if (!(std::isfinite(grid.half_range_mm) && grid.half_range_mm >= 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("grid half-range must be ≥ 0 mm, got {}", grid.half_range_mm));
  }
  const double n = grid_points_per_axis(grid.half_range_mm, grid.step_mm);
  if (n * n > max_points) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("a grid of ±{} mm by {} mm has {:.0f} × {:.0f} = {:.4g} points, more than {:.0f}",
                    grid.half_range_mm, grid.step_mm, n, n, n * n, max_points));
  }
  const int side = static_cast<int>(n);
  const int k = side / 2;
  const auto [first, second] = grid_plane_axes(grid.plane);
  std::vector<Pose> poses;
  poses.reserve(static_cast<std::size_t>(side) * side);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      Pose pose = grid.centre;
      pose.position_mm[first] += (i - k) * grid.step_mm;
      pose.position_mm[second] += (j - k) * grid.step_mm;
      poses.push_back(pose);
    }
  }
  return poses;
}

}  // namespace pkm::dynamics
