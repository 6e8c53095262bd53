#include "pipeline/plan_program.hpp"

#include <chrono>

#include "io/output_set.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline/run_report.hpp"
#include "planning/plan_output.hpp"

namespace pkm::pipeline {

Result<PlanProgramResult> plan_program(const Machine& machine, const PlanJob& job) {
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();

  PlanProgramResult result;
  if (job.law) {
    auto optimized = redundancy::optimize_program(*program, machine, *job.law);
    if (!optimized) return optimized.error();
    result.law_summary = redundancy::optimize_summary_json(*optimized, *job.law);
    *program = std::move(optimized->program);
    result.law = std::move(*optimized);
  }
  const auto started = std::chrono::steady_clock::now();
  auto plan = planning::plan_motion(machine, *program, job.plan);
  if (!plan) return plan.error();
  result.planning_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  planning::OutputOptions output;
  output.override_pct = job.plan.override_pct;
  output.evaluate_path_error = job.evaluate_path_error;
  output.dynamics = job.dynamics;
  output.elastic = job.elastic;
  output.stiffness = job.stiffness;
  output.dynamics_load = &job.dynamics_load;
  output.program_notes = program->notes;
  if (job.progress && plan->duration_s * job.plan.rate_hz > 200000) output.progress = job.progress;
  // The CSVs, the summary and the report replace the previous run's together or not at all.
  OutputSet outputs{"plan"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  auto run = planning::write_plan_outputs(*plan, machine, outputs, output);
  if (!run) return run.error();
  if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.summary = planning::summary_json(*plan, machine, *run);
  for (const std::string& note : program->notes) result.summary["warnings"].push_back(note);
  result.program_notes = program->notes;
  result.run = *run;
  result.plan = std::move(*plan);
  return result;
}

}  // namespace pkm::pipeline
