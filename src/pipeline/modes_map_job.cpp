#include "pipeline/modes_map_job.hpp"

#include "formats/frequency_map_csv.hpp"
#include "io/output_file.hpp"
#include "pipeline/plane_map_grid.hpp"

namespace pkm::pipeline {

Result<ModesMapJobResult> run_modes_map_job(const Machine& machine, const ModesMapJob& job) {
  auto model = dynamics::make_elastic_model(machine);
  if (!model) return model.error();
  auto grid = plane_map_grid(*machine.mechanism, job.grid);
  if (!grid) return grid.error();
  ModesMapJobResult out;
  out.points_per_axis = grid->points_per_axis;
  out.poses = std::move(grid->poses);
  out.points = dynamics::frequency_map(machine, *model, out.poses);
  out.summary = dynamics::summarise_frequency_map(out.points);
  if (!job.out_path.empty()) {
    const std::string csv = formats::frequency_map_csv(*machine.mechanism, out.poses, out.points);
    if (Status written = write_output_file(job.out_path, csv); !written) {
      Error e = written.error();
      e.message = job.out_name + ": " + e.message;
      return e;
    }
  }
  return out;
}

}  // namespace pkm::pipeline
