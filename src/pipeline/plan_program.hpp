#pragma once
// `pkm plan` (and Python's pkm.plan) as one library call: a part program file in, its planned servo-rate
// motion streamed once to the analyses asked for, to the output set (actuators.csv, path.csv, summary.json
// and, if asked, the HTML report) that replaces a previous run's only when all of it succeeded, and to the
// caller's own listener. With a drive control law, the coordinates the operation leaves free are
// chosen first (redundancy/optimize_program.hpp) and the rewritten program is planned.
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "analyses/plan_analyses.hpp"
#include "core/progress.hpp"
#include "formats/plan_tables.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "planning/motion_plan.hpp"
#include "planning/tick_observer.hpp"
#include "redundancy/optimize_program.hpp"

namespace pkm::pipeline {

struct PlanJob {
  std::string program_path;        ///< G-code, or CL data (told apart by content)
  ProgramOptions program_options;  ///< tool table, subroutine path, parameter file
  planning::PlanOptions plan;      ///< servo rate, override, blending tolerance (unset: the machine file's)
  std::optional<redundancy::OptimizeOptions> law;  ///< choose the free coordinates first
  bool evaluate_path_error = true;                 ///< FK of the actuators at every mid-period
  bool dynamics = false;  ///< drive forces, power and energy at every tick (forces.csv; docs/dynamics.md)
  statics::LoadModel dynamics_load;  ///< the process load in the dynamics (empty: gravity only)
  /// With `dynamics`: the elastic machine's response (response.csv; docs/dynamics_elastic.md)
  bool elastic = false;
  /// The tool's deflection under `dynamics_load`, the struts as springs (deflection.csv; docs/stiffness.md)
  bool stiffness = false;
  ProgressSink progress;      ///< told the phase, how far it is and the program line, now and then
  std::string out_directory;  ///< empty: no files (the caller listens to the ticks itself)
  /// The servo-rate tables as CSV files or as the groups of ticks.h5 (formats/plan_tables.hpp); the report
  /// reads either.
  formats::TickTables tick_tables = formats::TickTables::csv;
  std::string report_path;  ///< empty: no report
  /// Also listening to the run, after the files: every tick, and the analyses' ticks (e.g. into arrays).
  planning::TickObserver* listener = nullptr;
  analyses::PlanAnalysisSinks listener_sinks;
  /// Keep the whole plan (its path, samples and speeds) in the result. Without, the plan is made through its
  /// look-ahead window while the ticks stream, and memory does not grow with the program.
  bool keep_plan = false;
};

struct PlanProgramResult {
  std::optional<planning::MotionPlan> plan;       ///< with PlanJob::keep_plan
  planning::PlanStatistics statistics;            ///< what the plan used and where it is limited
  double path_error_bound_mm = 0.0;               ///< the bound every tick's path error was checked against
  analyses::PlanRun run;                          ///< what the streamed ticks measured
  double planning_s = 0.0;                        ///< wall time of the planning itself (not the writing)
  nlohmann::json summary;                         ///< summary.json as written
  std::optional<redundancy::OptimizeResult> law;  ///< with the law's job: what it chose
  nlohmann::json law_summary;                     ///< its summary (formats::optimize_summary_json)
  std::vector<std::string> program_notes;  ///< how the interpreter read the program (no tool table …)
};

/// Where the moves of each main-program line were written when that is elsewhere (a subroutine call): per
/// line ("12"), up to 8 distinct "file:line" in order of first appearance, the file by its name without the
/// folder. Empty when every move was written on its own line. summary.json's "subroutine_lines".
nlohmann::json subroutine_lines(const program::CanonicalProgram& program);

Result<PlanProgramResult> plan_program(const Machine& machine, const PlanJob& job);

}  // namespace pkm::pipeline
