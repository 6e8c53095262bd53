#include "pipeline/workspace_job.hpp"

#include "formats/workspace_output.hpp"
#include "io/output_set.hpp"
#include "pipeline/run_report.hpp"

namespace pkm::pipeline {
namespace {

Status write_workspace_outputs(const Machine& machine, const WorkspaceJob& job, const WorkspaceJobResult& r) {
  OutputSet outputs{"workspace"};
  if (Status s = outputs.use_directory(job.out_directory); !s) return s;
  if (Status s = formats::stage_workspace_files(outputs, machine, r.map, r.summary); !s) return s;
  if (Status s = stage_run_report(outputs, job.report_path); !s) return s;
  return outputs.commit();
}

}  // namespace

Result<WorkspaceJobResult> run_workspace_job(const Machine& machine, const WorkspaceJob& job) {
  workspace::WorkspaceMapOptions options = job.options;
  std::optional<CalibrationWorkspaceLayer> calibration;
  if (!job.calibration_plan.empty()) {
    auto layer = calibration_workspace_layer(machine, job.calibration_plan);
    if (!layer) return layer.error();
    if (job.warning)
      for (const std::string& warning : layer->plan.warnings) job.warning(warning);
    options.calibrated_error = layer->error_at_pose;
    calibration = std::move(*layer);
  }
  report_progress(job.progress, "mapping the grid");
  auto map = workspace::workspace_map(machine, job.grid, options);
  if (!map) return map.error();
  WorkspaceJobResult r{std::move(*map), {}, {}, std::move(calibration)};
  r.summary = workspace::summarise_workspace_map(r.map);
  if (!job.out_directory.empty()) {
    if (Status written = write_workspace_outputs(machine, job, r); !written) return written.error();
  }
  r.summary_json = formats::workspace_summary_json(machine, r.map, r.summary);
  return r;
}

}  // namespace pkm::pipeline
