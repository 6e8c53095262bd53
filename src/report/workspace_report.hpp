#pragma once
// The report of a `pkm workspace` run (workspace.csv, summary.json; docs/workspace.md): the summary as the
// report's table, the machine at the grid's centre with the grid's outline in the 3-D view, and a heat map
// per layer (`workspace_map`, docs/workspace.md): the status as categories, δρ, S_x, S_y, S_z, the condition
// number and the optional layers as colour scales. A 3-D grid is shown slice by slice. Read back from the
// files, as every report is.
#include <nlohmann/json.hpp>
#include <string>

#include "core/result.hpp"
#include "report/report_data.hpp"

namespace pkm::report {

/// The most cells a heat map shows along an axis: every k-th cell beyond (the centre's row kept), so a page
/// of a fine grid still opens quickly. A 3-D grid has more slices' worth of cells, so fewer along each.
inline constexpr int kWorkspaceSectionCellsPerAxis = 201;
inline constexpr int kWorkspaceGridCellsPerAxis = 41;

/// `workspace_map` from a workspace.csv and its summary (the grid's axes): {"file", "x_label", "y_label",
/// "x", "y", "slice_label", "slices", "status_names", "layers": [{"id", "label", "unit", "categorical",
/// "values": [slice][row][column]}]}. Errors name the file and line where it is malformed.
Result<nlohmann::json> workspace_map_json(const std::string& csv_path, const nlohmann::json& summary);

/// The whole report of the run in `directory` whose summary is `summary`; the machine file is the summary's
/// unless options.machine_file names another.
Result<nlohmann::json> workspace_report(const std::string& directory, const nlohmann::json& summary,
                                        const ReportOptions& options);

}  // namespace pkm::report
