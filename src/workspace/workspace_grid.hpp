#pragma once
// The cells of a workspace map (grid sections: planes, as Smirnov 2019,
// Figs. 158–162 and 180–182; or 3-D grids): two or three of the six pose coordinates stepped about a centre
// pose, the others kept at the centre's. A section of the translations is the pose grid of `pkm modes --map`
// and `pkm compliance --map` (dynamics/pose_grid.hpp): the centre is a cell, offsets are whole multiples of
// the step (not sums of steps), so the cells do not drift by rounding and the maps agree cell by cell.
#include <array>
#include <vector>

#include "dynamics/pose_grid.hpp"
#include "machine/mechanism.hpp"

namespace pkm::workspace {

/// One coordinate that varies over the grid.
struct GridAxis {
  int coordinate = 0;  ///< PoseVector index: 0, 1, 2 = x, y, z (mm); 3, 4, 5 = the convention's angles (rad)
  double half_range_mm_or_rad = 200.0;  ///< the axis covers the centre ± this (mm, or rad for an angle)
  double step_mm_or_rad = 20.0;         ///< (mm, or rad for an angle)
};

struct WorkspaceGrid {
  Pose centre;
  /// Two axes (a section through the centre) or three (a 3-D grid); the first runs fastest in the cells'
  /// order, then the second, then the third.
  std::vector<GridAxis> axes;
};

/// More cells than this are almost always a mistyped step: ~10 µs each on the ch5 hexapod (docs/workspace.md)
/// and ~120 bytes of CSV, so the cap is seconds and 120 MB.
inline constexpr double kMaxWorkspaceCells = 1'000'000;

/// The section of the translations in `plane` through `centre` (the grid of dynamics::plane_grid_poses).
WorkspaceGrid plane_section(const Pose& centre, dynamics::GridPlane plane, double half_range_mm,
                            double step_mm);
/// The 3-D grid of tool positions about `centre`: x, y and z each ± `half_range_mm` by `step_mm`.
WorkspaceGrid position_grid(const Pose& centre, double half_range_mm, double step_mm);

/// ok, or bad_input naming what is wrong: not two or three axes, an axis twice or out of 0…5, a coordinate
/// the mechanism does not control (the tripod's x: its constraints set it), a step that is not a positive
/// finite number, a negative or non-finite half-range, more than `max_cells` cells.
Status validate_grid(const Mechanism& mechanism, const WorkspaceGrid& grid,
                     double max_cells = kMaxWorkspaceCells);

/// The poses of a valid grid's cells, made without allocating (the map's threads ask for them one by one).
class GridCells {
 public:
  GridCells(const WorkspaceGrid& grid, AngleConvention convention);

  long count() const { return count_; }
  int axis_count() const { return axes_; }
  /// Points along axis a: 2k + 1 (dynamics::grid_points_per_axis).
  int points(int axis) const { return points_[static_cast<std::size_t>(axis)]; }
  /// The cell's index along each axis (0 … points − 1; the third is 0 for a section).
  std::array<int, 3> indices(long cell) const noexcept;
  /// The cell's pose: the centre with the axes' offsets (i − k)·step. Translations move the centre's tool
  /// point and keep its rotation exactly; angles go through the convention.
  Pose pose(long cell) const noexcept;

 private:
  WorkspaceGrid grid_;
  AngleConvention convention_;
  PoseVector centre_coordinates_;
  int axes_ = 0;
  bool angles_ = false;
  std::array<int, 3> points_{1, 1, 1};
  long count_ = 0;
};

}  // namespace pkm::workspace
