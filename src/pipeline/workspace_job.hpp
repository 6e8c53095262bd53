#pragma once
// `pkm workspace` (and Python's pkm.workspace) as one library call: the workspace map over a plane section
// or a 3-D grid (workspace/workspace_map.hpp), on request with the layer of the tool error predicted after
// measuring a calibration plan (calibration_workspace.hpp), written as workspace.csv and summary.json
// (formats/workspace_output.hpp) with, if asked, the HTML report, as one output set.
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "pipeline/calibration_workspace.hpp"
#include "workspace/workspace_map.hpp"
#include "workspace/workspace_summary.hpp"

namespace pkm::pipeline {

struct WorkspaceJob {
  workspace::WorkspaceGrid grid;
  workspace::WorkspaceMapOptions options;  ///< its calibrated_error is set from calibration_plan when given
  std::string calibration_plan;            ///< the directory `pkm calibrate plan` wrote; empty: no such layer
  std::string out_directory;               ///< workspace.csv and summary.json; empty: not written
  std::string report_path;                 ///< the HTML report (with out_directory); empty: none
  ProgressSink progress;                   ///< told the phase
  /// Told each warning as it arises (the calibration plan's differences from this machine); may be empty.
  std::function<void(std::string_view)> warning;
};

struct WorkspaceJobResult {
  workspace::WorkspaceMap map;
  workspace::WorkspaceMapSummary summary;
  nlohmann::json summary_json;  ///< formats::workspace_summary_json: summary.json as written
  std::optional<CalibrationWorkspaceLayer> calibration;  ///< with calibration_plan
};

/// Refuses a grid workspace::workspace_map refuses and a calibration plan that cannot be read for the
/// machine. Everything is computed before the directory is touched: a failure leaves no directory behind.
Result<WorkspaceJobResult> run_workspace_job(const Machine& machine, const WorkspaceJob& job);

}  // namespace pkm::pipeline
