#include "workspace/workspace_grid.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::workspace {
namespace {

Error workspace_grid_error(std::string message) {
  return make_error(ErrorCode::bad_input, std::move(message));
}

// The coordinate's name and unit for messages: "x (mm)", "B (deg)".
std::string workspace_axis_name(const Mechanism& mechanism, int coordinate) {
  const auto names = pose_coordinate_names(mechanism);
  return fmt::format("{} ({})", names[static_cast<std::size_t>(coordinate)], coordinate < 3 ? "mm" : "rad");
}

}  // namespace

WorkspaceGrid plane_section(const Pose& centre, dynamics::GridPlane plane, double half_range_mm,
                            double step_mm) {
  const auto [first, second] = dynamics::grid_plane_axes(plane);
  return {centre, {{first, half_range_mm, step_mm}, {second, half_range_mm, step_mm}}};
}

WorkspaceGrid position_grid(const Pose& centre, double half_range_mm, double step_mm) {
  return {centre, {{0, half_range_mm, step_mm}, {1, half_range_mm, step_mm}, {2, half_range_mm, step_mm}}};
}

Status validate_grid(const Mechanism& mechanism, const WorkspaceGrid& grid, double max_cells) {
  const std::size_t n = grid.axes.size();
  if (n != 2 && n != 3) {
    return workspace_grid_error(
        fmt::format("a workspace map varies 2 coordinates (a section) or 3 (a 3-D grid), not {}", n));
  }
  const AxisMask mask = mechanism.controlled_axes();
  double cells = 1.0;
  for (std::size_t a = 0; a < n; ++a) {
    const GridAxis& axis = grid.axes[a];
    if (axis.coordinate < 0 || axis.coordinate > 5) {
      return workspace_grid_error(fmt::format(
          "grid axis {}: coordinate {} is not one of 0…5 (x, y, z, three angles)", a + 1, axis.coordinate));
    }
    for (std::size_t b = 0; b < a; ++b) {
      if (grid.axes[b].coordinate == axis.coordinate) {
        return workspace_grid_error(fmt::format("grid axes {} and {} are both {}", b + 1, a + 1,
                                                workspace_axis_name(mechanism, axis.coordinate)));
      }
    }
    // An uncontrolled coordinate is set by the mechanism's constraints (complete_pose): stepping it would
    // give cells that are all the same pose.
    if (!mask.controlled[static_cast<std::size_t>(axis.coordinate)]) {
      return workspace_grid_error(
          fmt::format("the {} does not control {}: a map varies the coordinates it controls ({})",
                      to_string(mechanism.type()), workspace_axis_name(mechanism, axis.coordinate),
                      fmt::join(controlled_coordinate_names(mechanism), ", ")));
    }
    if (!(std::isfinite(axis.step_mm_or_rad) && axis.step_mm_or_rad > 0.0)) {
      return workspace_grid_error(fmt::format("grid step along {} must be a positive number, got {}",
                                              workspace_axis_name(mechanism, axis.coordinate),
                                              axis.step_mm_or_rad));
    }
    if (!(std::isfinite(axis.half_range_mm_or_rad) && axis.half_range_mm_or_rad >= 0.0)) {
      return workspace_grid_error(fmt::format("grid half-range along {} must be ≥ 0, got {}",
                                              workspace_axis_name(mechanism, axis.coordinate),
                                              axis.half_range_mm_or_rad));
    }
    cells *= dynamics::grid_points_per_axis(axis.half_range_mm_or_rad, axis.step_mm_or_rad);
  }
  if (cells > max_cells) {
    return workspace_grid_error(fmt::format("the grid has {:.4g} cells, more than {:.0f}", cells, max_cells));
  }
  return ok_status();
}

GridCells::GridCells(const WorkspaceGrid& grid, AngleConvention convention)
    : grid_(grid), convention_(convention), centre_coordinates_(vector_from_pose(convention, grid.centre)) {
  axes_ = static_cast<int>(grid_.axes.size() < 3 ? grid_.axes.size() : 3);
  count_ = axes_ > 0 ? 1 : 0;
  for (int a = 0; a < axes_; ++a) {
    const GridAxis& axis = grid_.axes[static_cast<std::size_t>(a)];
    points_[static_cast<std::size_t>(a)] =
        static_cast<int>(dynamics::grid_points_per_axis(axis.half_range_mm_or_rad, axis.step_mm_or_rad));
    count_ *= points_[static_cast<std::size_t>(a)];
    if (axis.coordinate >= 3) angles_ = true;
  }
}

std::array<int, 3> GridCells::indices(long cell) const noexcept {
  std::array<int, 3> at{0, 0, 0};
  for (int a = 0; a < axes_; ++a) {
    const auto k = static_cast<std::size_t>(a);
    at[k] = static_cast<int>(cell % points_[k]);
    cell /= points_[k];
  }
  return at;
}

Pose GridCells::pose(long cell) const noexcept {
  const std::array<int, 3> at = indices(cell);
  Pose pose = grid_.centre;
  PoseVector coordinates = centre_coordinates_;
  for (int a = 0; a < axes_; ++a) {
    const auto k = static_cast<std::size_t>(a);
    const GridAxis& axis = grid_.axes[k];
    const double offset = (at[k] - points_[k] / 2) * axis.step_mm_or_rad;
    if (axis.coordinate < 3) {
      pose.position_mm[axis.coordinate] += offset;
    } else {
      coordinates[axis.coordinate] += offset;
    }
  }
  if (angles_) pose.rotation = pose_from_vector(convention_, coordinates).rotation;
  return pose;
}

}  // namespace pkm::workspace
