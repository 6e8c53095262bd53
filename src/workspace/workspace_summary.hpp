#pragma once
// What a workspace map says in a few numbers: how many cells each status has (and which actuators stop the
// machine how often: a glide's working zone is bounded by its carriages' travel), and each layer's extremes
// over the cells where the machine can stand (status ok), with the cells they are at. δρ_MAX of Smirnov
// 2019, eq. 146 is the error amplification's maximum here.
#include <array>

#include "workspace/workspace_layers.hpp"
#include "workspace/workspace_map.hpp"

namespace pkm::workspace {

struct LayerExtremes {
  long cells = 0;  ///< ok cells with a value
  double min = WorkspaceCell::kNone;
  double max = WorkspaceCell::kNone;
  long min_cell = -1;  ///< the first cell of the smallest value; −1 when no cell has one
  long max_cell = -1;
};

struct WorkspaceMapSummary {
  long cells = 0;
  std::array<long, kCellStatusCount> status_cells{};  ///< by CellStatus
  std::array<long, kMaxActuators>
      actuator_range_cells{};  ///< actuator_range cells by the actuator stopping them
  /// Sign of det J over the ok cells: a change of sign inside the reachable zone means a singularity runs
  /// through it.
  long determinant_positive = 0;
  long determinant_negative = 0;
  std::array<LayerExtremes, kLayerCount> layers{};  ///< by Layer, over the ok cells
};

WorkspaceMapSummary summarise_workspace_map(const WorkspaceMap& map);

}  // namespace pkm::workspace
