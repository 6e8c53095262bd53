#include "pipeline/plan_program.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "formats/optimize_summary.hpp"
#include "formats/plan_files.hpp"
#include "io/output_set.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline/run_report.hpp"
#include "planning/plan_producer.hpp"
#include "planning/run_accuracy.hpp"

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

namespace {

/// Both sinks of an analysis' ticks, the files' first.
template <class Tick>
std::function<Status(const Tick&)> both(std::function<Status(const Tick&)> first,
                                        std::function<Status(const Tick&)> second) {
  if (!first) return second;
  if (!second) return first;
  return [first = std::move(first), second = std::move(second)](const Tick& tick) -> Status {
    if (Status kept = first(tick); !kept) return kept;
    return second(tick);
  };
}

analyses::PlanAnalysisSinks both(analyses::PlanAnalysisSinks first,
                                 const analyses::PlanAnalysisSinks& second) {
  return {both(std::move(first.dynamics), second.dynamics), both(std::move(first.elastic), second.elastic),
          both(std::move(first.deflection), second.deflection)};
}

/// summary.json: the run's summary with what the program's reading adds, the interpreter's notes among the
/// warnings and where a calling line's moves were written.
nlohmann::json summary_with_program(const planning::MotionPlan& plan, const Machine& machine,
                                    const analyses::PlanRun& run, const std::vector<std::string>& notes,
                                    const nlohmann::json& called) {
  nlohmann::json summary = formats::plan_summary_json(plan, machine, run);
  for (const std::string& note : notes) summary["warnings"].push_back(note);
  if (!called.empty()) summary["subroutine_lines"] = called;
  return summary;
}

/// The planned motion streamed once: to the analyses the job asks for, the output files (when the job has a
/// folder) and the job's listener. The files are staged in `outputs`, for the caller to commit.
Result<analyses::PlanRun> stream_planned(const Machine& machine, const PlanJob& job,
                                         const planning::MotionPlan& plan, planning::PlanProducer* source,
                                         const std::vector<std::string>& notes, const nlohmann::json& called,
                                         OutputSet& outputs) {
  planning::StreamOptions stream{job.plan.override_pct, job.evaluate_path_error, job.progress, source};
  const analyses::PlanAnalysisOptions wanted{job.dynamics, job.elastic, job.stiffness, &job.dynamics_load};
  std::optional<formats::PlanFiles> files;
  std::vector<planning::TickObserver*> observers;
  analyses::PlanAnalysisSinks sinks = job.listener_sinks;
  if (!job.out_directory.empty()) {
    if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
    files.emplace(machine, wanted, job.tick_tables);
    if (Status opened = files->open(outputs); !opened) return opened.error();
    observers.push_back(&*files);
    sinks = both(files->analysis_sinks(), job.listener_sinks);
  }
  if (job.listener != nullptr) observers.push_back(job.listener);
  auto run = analyses::stream_plan_with_analyses(plan, machine, stream, wanted, sinks, observers);
  if (!run) return run.error();
  if (files) {
    const nlohmann::json summary = summary_with_program(plan, machine, *run, notes, called);
    if (Status finished = files->finish(summary); !finished) return finished.error();
  }
  return run;
}

}  // namespace

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
    result.law_summary = formats::optimize_summary_json(*optimized, *job.law);
    *program = std::move(optimized->program);
    result.law = std::move(*optimized);
  }
  const auto started = std::chrono::steady_clock::now();
  planning::PlanOptions plan_options = job.plan;
  plan_options.progress = job.progress;
  // A whole plan for the caller, or the plan made twice through its look-ahead window: once for its length
  // in time, its statistics and the refusals that come before any output (the bound on the ticks), then
  // again while the ticks stream, so memory is the window's, not the program's.
  std::unique_ptr<planning::StreamedPlan> streamed;
  if (job.keep_plan) {
    auto whole = planning::plan_motion(machine, *program, plan_options);
    if (!whole) return whole.error();
    streamed = std::make_unique<planning::StreamedPlan>(std::move(*whole), nullptr);
  } else {
    auto started_plan = planning::start_streamed_plan(machine, *program, plan_options);
    if (!started_plan) return started_plan.error();
    streamed = std::move(*started_plan);
  }
  const planning::MotionPlan& plan = streamed->plan;
  result.planning_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  // The tables, the summary and the report replace the previous run's together or not at all.
  OutputSet outputs{"plan"};
  auto run = stream_planned(machine, job, plan, streamed->source.get(), program->notes, called, outputs);
  if (!run) return run.error();
  if (!job.out_directory.empty()) {
    if (!job.report_path.empty()) report_progress(job.progress, "writing the report");
    if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
    if (Status committed = outputs.commit(); !committed) return committed.error();
  }
  result.summary = summary_with_program(plan, machine, *run, program->notes, called);
  result.summary["program_format"] = format;
  result.program_notes = program->notes;
  result.run = std::move(*run);
  result.statistics = plan.statistics;
  result.path_error_bound_mm = planning::path_error_bound_mm(plan);
  if (job.keep_plan) result.plan = std::move(streamed->plan);
  return result;
}

}  // namespace pkm::pipeline
