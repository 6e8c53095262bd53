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
#include "pipeline/program_stream.hpp"
#include "pipeline/run_report.hpp"
#include "planning/plan_producer.hpp"
#include "planning/run_accuracy.hpp"

namespace pkm::pipeline {

nlohmann::json subroutine_lines(const program::CanonicalProgram& program) {
  // The path and the ticks keep only the main program's line, so the report could show a subroutine call's
  // text but not the lines that moved the tool; this keeps where they were written, a few per calling line.
  SubroutineLines places;
  for (const program::CanonicalMove& move : program.moves) places.add(move);
  return places.json(program.files);
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

/// The program planned: read whole and planned whole (a law rewrites it, or the caller keeps the plan), or
/// read and planned as it is read (memory bounded by the look-ahead window).
struct ProgramPlan {
  /// Streamed: without its moves. On the heap: the plan's source reads it where it is.
  std::unique_ptr<program::CanonicalProgram> program;
  /// Streamed: what the reader learns as it reads (the places of the moves, the program's format and notes),
  /// whole once the plan has taken the last move. Before `plan`: its reader writes them until it stops.
  std::unique_ptr<SubroutineLines> places;
  std::unique_ptr<program::CanonicalProgram> header;
  std::unique_ptr<planning::StreamedPlan> plan;
  nlohmann::json called;  ///< subroutine_lines

  /// After the stream: the program's notes, format and places from the reader.
  void finish_reading() {
    if (!header) return;
    called = places->json(header->files);
    program->format = header->format;
    program->notes = header->notes;
  }
};

/// The planned motion streamed once: to the analyses the job asks for, the output files (when the job has a
/// folder) and the job's listener. The files are staged in `outputs`, for the caller to commit.
Result<analyses::PlanRun> stream_planned(const Machine& machine, const PlanJob& job, ProgramPlan& planned,
                                         OutputSet& outputs) {
  const planning::MotionPlan& plan = planned.plan->plan;
  planning::StreamOptions stream{job.plan.override_pct, job.evaluate_path_error, job.progress,
                                 planned.plan->source.get()};
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
  planned.finish_reading();
  if (files) {
    const nlohmann::json summary =
        summary_with_program(plan, machine, *run, planned.program->notes, planned.called);
    if (Status finished = files->finish(summary); !finished) return finished.error();
  }
  return run;
}

Result<ProgramPlan> plan_whole_program(const Machine& machine, const PlanJob& job,
                                       const planning::PlanOptions& options, PlanProgramResult& result) {
  report_progress(job.progress, "reading the program");
  auto read = load_program_for(machine, job.program_path, job.program_options);
  if (!read) return read.error();
  ProgramPlan planned;
  planned.program = std::make_unique<program::CanonicalProgram>(std::move(*read));
  program::CanonicalProgram* program = planned.program.get();
  // Before the law rewrites the program: the places of its moves are the ones the user wrote.
  planned.called = subroutine_lines(*program);
  if (job.law) {
    report_progress(job.progress, "choosing the free coordinates");
    auto optimized = redundancy::optimize_program(*program, machine, *job.law);
    if (!optimized) return optimized.error();
    result.law_summary = formats::optimize_summary_json(*optimized, *job.law);
    *program = std::move(optimized->program);
    result.law = std::move(*optimized);
  }
  const auto started = std::chrono::steady_clock::now();
  if (job.keep_plan) {
    auto whole = planning::plan_motion(machine, *program, options);
    if (!whole) return whole.error();
    planned.plan = std::make_unique<planning::StreamedPlan>();
    planned.plan->plan = std::move(*whole);
  } else {
    auto streamed = planning::start_streamed_plan(machine, *program, options);
    if (!streamed) return streamed.error();
    planned.plan = std::move(*streamed);
  }
  result.planning_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return planned;
}

/// The program read on a thread of its own while the plan is made from its moves and the ticks stream.
Result<ProgramPlan> plan_streamed_program(const Machine& machine, const PlanJob& job,
                                          const planning::PlanOptions& options) {
  report_progress(job.progress, "reading the program");
  auto started = start_streamed_program_plan(machine, job.program_path, job.program_options, options);
  if (!started) return started.error();
  ProgramPlan planned;
  planned.program = std::move(started->program);
  planned.places = std::move(started->places);
  planned.header = std::move(started->header);
  planned.plan = std::move(started->plan);
  return planned;
}

}  // namespace

Result<PlanProgramResult> plan_program(const Machine& machine, const PlanJob& job) {
  PlanProgramResult result;
  planning::PlanOptions plan_options = job.plan;
  plan_options.progress = job.progress;
  auto planned = job.law || job.keep_plan ? plan_whole_program(machine, job, plan_options, result)
                                          : plan_streamed_program(machine, job, plan_options);
  if (!planned) return planned.error();
  const planning::MotionPlan& plan = planned->plan->plan;

  // The tables, the summary and the report replace the previous run's together or not at all.
  OutputSet outputs{"plan"};
  auto run = stream_planned(machine, job, *planned, outputs);
  if (!run) return run.error();
  if (planned->plan->source) result.planning_s = planned->plan->source->planning_s();
  const program::CanonicalProgram* program = planned->program.get();
  const nlohmann::json& called = planned->called;
  const std::string& format = program->format;
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
  if (job.keep_plan) result.plan = std::move(planned->plan->plan);
  return result;
}

}  // namespace pkm::pipeline
