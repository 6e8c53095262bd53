#pragma once
// The files of `pkm workspace` (docs/workspace.md): workspace.csv, one row per cell in the grid's order, and
// summary.json, the grid and the summary (workspace_summary.hpp). Staged into an output set, so a run that
// fails half way leaves the previous run's files as they were (io/output_set.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/output_set.hpp"
#include "workspace/workspace_summary.hpp"

namespace pkm::formats {

inline constexpr const char* kWorkspaceCsv = "workspace.csv";
inline constexpr const char* kWorkspaceSummaryJson = "summary.json";

/// "q3_max", "base_joint_2", "condition_number", "" for none: which limit stops a cell (1-based numbers).
std::string limit_text(const workspace::WorkspaceCell& cell);

/// The CSV column of a grid axis: "x_mm", "B_deg" (the pose columns of dynamics/pose_grid_columns.hpp).
std::string axis_column(const Mechanism& mechanism, int coordinate);

/// The CSV: the pose columns of `--pose` (x_mm … in degrees), status, limit, det_sign, condition_number,
/// delta_rho, S_x, S_y, S_z, then the optional layers the map has (workspace_layers.hpp). Values are empty
/// where a cell has none.
std::string workspace_csv(const Mechanism& mechanism, const workspace::WorkspaceMap& map);

/// summary.json: "kind": "workspace", the machine file, the grid (centre and axes in the units users give:
/// mm and degrees), the cells per status and per stopping actuator, the det J signs, and per layer its
/// extremes over the ok cells with their poses.
nlohmann::json workspace_summary_json(const Machine& machine, const workspace::WorkspaceMap& map,
                                      const workspace::WorkspaceMapSummary& summary);

/// Stages workspace.csv and summary.json into `outputs` (its directory must be in use).
Status stage_workspace_files(OutputSet& outputs, const Machine& machine, const workspace::WorkspaceMap& map,
                             const workspace::WorkspaceMapSummary& summary);

}  // namespace pkm::formats
