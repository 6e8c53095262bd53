#pragma once
// A plane grid of poses about a centre pose: the tool point moved along two base-frame axes by whole steps
// each side of the centre, the third coordinate and the orientation kept. Maps over the workspace
// (frequency_map.hpp) are sampled on it. The centre is always a grid point, so a map can be checked there
// against the single-pose computation, and offsets are whole multiples of the step (not sums of steps), so
// the grid does not drift by rounding.
#include <array>
#include <string_view>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"

namespace pkm::dynamics {

enum class GridPlane { xy, xz, yz };

/// "xy", "xz", "yz".
const char* to_string(GridPlane plane);
/// The plane named "xy", "xz" or "yz".
Result<GridPlane> grid_plane_from_string(std::string_view name);
/// The plane's two base-frame axes (0 x, 1 y, 2 z); the first runs fastest in the grid's order.
std::array<int, 2> grid_plane_axes(GridPlane plane);

struct PlaneGrid {
  Pose centre;
  GridPlane plane = GridPlane::xy;
  double half_range_mm = 200.0;  ///< the grid covers the centre ± this along both axes
  double step_mm = 20.0;
};

/// Points along each axis, 2k + 1: the centre and k = ⌊half_range / step⌋ whole steps each side (a ratio
/// within 10⁻⁹ of a whole number counts as that number, so ±200 mm by 0.1 mm reaches ±200). A double,
/// because a tiny step over a wide range must be refused before its count overflows an integer.
double grid_points_per_axis(double half_range_mm, double step_mm);

/// The grid's poses, index i + n·j at offsets (i − k)·step along the plane's first axis and (j − k)·step
/// along its second (n = 2k + 1). Fails (bad_input) for a step that is not a positive finite number, a
/// negative or non-finite half-range, or more than `max_points` poses.
Result<std::vector<Pose>> plane_grid_poses(const PlaneGrid& grid, double max_points);

}  // namespace pkm::dynamics
