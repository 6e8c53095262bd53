#include "pipeline/plan_program.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

#include "io/output_set.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline/run_report.hpp"
#include "planning/plan_output.hpp"

namespace pkm::pipeline {

nlohmann::json subroutine_lines(const program::CanonicalProgram& program) {
  // The path and the ticks keep only the main program's line, so the report could show a subroutine call's
  // text but not the lines that moved the tool; this keeps where they were written, a few per calling line.
  constexpr std::size_t kMaxPlaces = 8;
  std::map<int, std::vector<std::string>> places;
  std::vector<std::string> names;
  for (const std::string& file : program.files)
    names.push_back(std::filesystem::path(file).filename().string());
  for (const program::CanonicalMove& move : program.moves) {
    if (move.source_file == 0 && move.source_line == move.line) continue;
    if (move.line <= 0 || move.source_line <= 0) continue;
    std::vector<std::string>& here = places[move.line];
    if (here.size() >= kMaxPlaces) continue;
    const std::size_t file = static_cast<std::size_t>(move.source_file);
    const std::string name = file < names.size() ? names[file] : std::string("?");
    std::string place = name + ":" + std::to_string(move.source_line);
    if (std::find(here.begin(), here.end(), place) == here.end()) here.push_back(std::move(place));
  }
  nlohmann::json out = nlohmann::json::object();
  for (auto& [line, list] : places) out[std::to_string(line)] = std::move(list);
  return out;
}

Result<PlanProgramResult> plan_program(const Machine& machine, const PlanJob& job) {
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();

  PlanProgramResult result;
  // Before the law rewrites the program: the places of its moves are the ones the user wrote.
  nlohmann::json called = subroutine_lines(*program);
  const std::string format = program->format;
  if (job.law) {
    report_progress(job.progress, "choosing the free coordinates");
    auto optimized = redundancy::optimize_program(*program, machine, *job.law);
    if (!optimized) return optimized.error();
    result.law_summary = redundancy::optimize_summary_json(*optimized, *job.law);
    *program = std::move(optimized->program);
    result.law = std::move(*optimized);
  }
  const auto started = std::chrono::steady_clock::now();
  planning::PlanOptions plan_options = job.plan;
  plan_options.progress = job.progress;
  auto plan = planning::plan_motion(machine, *program, plan_options);
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
  output.subroutine_lines = called;
  output.progress = job.progress;
  // The CSVs, the summary and the report replace the previous run's together or not at all.
  OutputSet outputs{"plan"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  auto run = planning::write_plan_outputs(*plan, machine, outputs, output);
  if (!run) return run.error();
  if (!job.report_path.empty()) report_progress(job.progress, "writing the report");
  if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.summary = planning::summary_json(*plan, machine, *run);
  result.summary["program_format"] = format;
  for (const std::string& note : program->notes) result.summary["warnings"].push_back(note);
  if (!called.empty()) result.summary["subroutine_lines"] = std::move(called);
  result.program_notes = program->notes;
  result.run = *run;
  result.plan = std::move(*plan);
  return result;
}

}  // namespace pkm::pipeline
