#pragma once
// pkm workspace's grid from the command line: --centre, --plane, --range-mm and --step-mm as `pkm modes
// --map` and `pkm compliance --map` take them (map_grid.hpp), --plane also naming two coordinates ("x,B")
// with
// --range-deg and --step-deg for angles, and --grid3d for a 3-D grid of positions. The library checks the
// grid (workspace/workspace_grid.hpp); here the flags are read and the messages name them.
#include <string>

#include "map_grid.hpp"
#include "workspace/workspace_grid.hpp"

namespace pkm::cli {

struct WorkspaceGridArguments {
  MapGridArguments section;  ///< --centre, --plane, --range-mm, --step-mm (map_grid.hpp's defaults)
  double half_range_deg = 10.0;
  double step_deg = 1.0;
  bool grid3d = false;
};

/// The grid of the flags for `mechanism`. Errors (bad_input) name the flag: a centre that is no pose, a plane
/// that names no two coordinates or one the machine does not control, more than kMaxMapGridPoints cells.
Result<workspace::WorkspaceGrid> workspace_grid_from(const Mechanism& mechanism,
                                                     const WorkspaceGridArguments& arguments);

/// "the xz plane through 0, 0, 700, 0, 0, 0, ±200 mm by 20 mm": the grid in words.
std::string describe_workspace_grid(const Mechanism& mechanism, const workspace::WorkspaceGrid& grid);

}  // namespace pkm::cli
