#include "workspace/workspace_summary.hpp"

#include <cmath>

namespace pkm::workspace {

WorkspaceMapSummary summarise_workspace_map(const WorkspaceMap& map) {
  WorkspaceMapSummary s;
  s.cells = static_cast<long>(map.cells.size());
  for (long i = 0; i < s.cells; ++i) {
    const WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    ++s.status_cells[static_cast<std::size_t>(cell.status)];
    if (cell.status == CellStatus::actuator_range && cell.limit_index >= 0) {
      ++s.actuator_range_cells[static_cast<std::size_t>(cell.limit_index)];
    }
    if (cell.status != CellStatus::ok) continue;
    s.determinant_positive += cell.determinant_sign > 0 ? 1 : 0;
    s.determinant_negative += cell.determinant_sign < 0 ? 1 : 0;
    for (const LayerInfo& info : workspace_layers()) {
      const double v = layer_value(cell, info.layer);
      if (std::isnan(v)) continue;
      LayerExtremes& e = s.layers[static_cast<std::size_t>(info.layer)];
      ++e.cells;
      // Strict comparisons: of equal values the first cell in the grid's order is kept.
      if (e.min_cell < 0 || v < e.min) {
        e.min = v;
        e.min_cell = i;
      }
      if (e.max_cell < 0 || v > e.max) {
        e.max = v;
        e.max_cell = i;
      }
    }
  }
  return s;
}

}  // namespace pkm::workspace
