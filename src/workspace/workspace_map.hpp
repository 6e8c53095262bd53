#pragma once
// A workspace map (docs/workspace.md): every cell of a grid (workspace_grid.hpp) evaluated in
// parallel on all cores (oneTBB): its status, which limit stops it, and its Jacobian measures
// (workspace_cell.hpp), and, where asked for, the lowest stiffness, the lowest natural frequency and the
// predicted error after calibration. Cells are independent and each is computed by the same code whichever
// thread runs it, so the map is the same, bit for bit, on one thread or many.
#include <functional>
#include <vector>

#include "machine/machine.hpp"
#include "workspace/workspace_cell.hpp"
#include "workspace/workspace_grid.hpp"

namespace pkm::workspace {

/// The tool-position error predicted at a pose after calibration (mm; calibration's identified parameters
/// and their uncertainty). Called from the map's threads at the same time: it must be safe to call
/// concurrently (a function of the pose and of data it only reads).
using CalibratedErrorAtPose = std::function<double(const Pose&)>;

struct WorkspaceMapOptions {
  /// The weakest principal translational stiffness (N/µm) of the machine's compliance model
  /// (stiffness/compliance_model.hpp: `stiffness:`, or the `dynamics:` springs). Needs strut stiffness.
  bool stiffness = false;
  /// The lowest natural frequency (Hz) of the elastic machine (dynamics/natural_frequencies.hpp: the drives
  /// clamped, about the static equilibrium under gravity). Needs `dynamics:` with strut stiffness.
  bool frequencies = false;
  /// The predicted error after calibration; empty: no such layer.
  CalibratedErrorAtPose calibrated_error;
  /// Threads: 0 (or less) = every core (TBB's default), 1 = the calling thread only; at most the cores.
  int threads = 0;
};

struct WorkspaceMap {
  WorkspaceGrid grid;
  std::vector<int> points_per_axis;  ///< as GridCells::points
  std::vector<WorkspaceCell> cells;  ///< in the grid's order, its first axis fastest
  bool has_stiffness = false;
  bool has_frequencies = false;
  bool has_calibrated_error = false;
};

/// The map of `machine` over `grid`. Fails (bad_input) for a grid validate_grid refuses, and where a layer
/// asked for needs what the machine file does not describe (no strut stiffness, no `dynamics:`), with the
/// error that names the file and key. The machine must not change while the map is computed.
Result<WorkspaceMap> workspace_map(const Machine& machine, const WorkspaceGrid& grid,
                                   const WorkspaceMapOptions& options = {});

}  // namespace pkm::workspace
