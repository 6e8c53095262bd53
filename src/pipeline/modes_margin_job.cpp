#include "pipeline/modes_margin_job.hpp"

#include "formats/modes_margin_output.hpp"
#include "io/atomic_file.hpp"
#include "planning/motion_plan.hpp"

namespace pkm::pipeline {

Result<ModesMarginJobResult> run_modes_margin_job(const Machine& machine, const ModesMarginJob& job) {
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  planning::PlanOptions plan_options;
  plan_options.progress = job.progress;
  auto plan = planning::plan_motion(machine, *program, plan_options);
  if (!plan) return plan.error();
  report_progress(job.progress, "assembly-mode margin along the path");
  auto margin = workspace::modes_margin_along_plan(machine, *plan, job.margin);
  if (!margin) return margin.error();
  ModesMarginJobResult result{std::move(*margin), {}};
  result.summary = formats::modes_margin_summary_json(machine, result.margin);
  if (!job.out_path.empty()) {
    const std::string csv = formats::modes_margin_csv(*machine.mechanism, result.margin);
    if (Status written = write_file_atomically(job.out_path, csv); !written) return written.error();
    result.summary["out"] = job.out_path;
  }
  return result;
}

}  // namespace pkm::pipeline
