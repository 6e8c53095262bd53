#include "pipeline/compliance_map_job.hpp"

#include "formats/stiffness_csv.hpp"
#include "pipeline/plane_map_grid.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::pipeline {

Result<ComplianceMapJobResult> run_compliance_map_job(const Machine& machine, const ComplianceMapJob& job) {
  auto parameters = stiffness::strut_stiffness_of(machine);
  if (!parameters) return parameters.error();
  auto grid = plane_map_grid(*machine.mechanism, job.grid);
  if (!grid) return grid.error();
  report_progress(job.progress, "stiffness over the grid");
  auto points = stiffness::stiffness_map(grid->poses, stiffness::strut_compliance_at(machine, *parameters));
  if (!points) return points.error();
  if (!job.out_path.empty()) {
    if (Status written =
            formats::write_stiffness_map_csv(job.out_path, *machine.mechanism, grid->poses, *points);
        !written) {
      Error e = written.error();
      e.message = job.out_name + ": " + e.message;
      return e;
    }
  }
  ComplianceMapJobResult out{grid->points_per_axis, std::move(grid->poses), std::move(*points), {}};
  out.summary = stiffness::summarise_stiffness_map(out.points);
  return out;
}

}  // namespace pkm::pipeline
