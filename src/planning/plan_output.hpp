#pragma once
// Writing a planned run: DIR/actuators.csv (time and every actuator position per servo tick), DIR/path.csv
// (commanded tool pose per tick, program coordinates, with the source line), DIR/summary.json, and with
// OutputOptions::dynamics DIR/forces.csv (drive forces: total, static, dynamic; drive power), and with
// OutputOptions::elastic DIR/response.csv (the elastic machine's deviation from the commanded pose), and with
// OutputOptions::stiffness DIR/deflection.csv (the tool's deflection under the process load).
// The files join an OutputSet (io/output_set.hpp): they replace the previous run's only together, when the
// whole run succeeded, so a failed run leaves the previous run complete and nothing of its own.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "core/result.hpp"
#include "io/output_set.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/run_monitor.hpp"
#include "statics/load_model.hpp"

namespace pkm::planning {

struct OutputOptions {
  double override_pct = 100.0;
  bool evaluate_path_error = true;
  /// Also the rigid-body drive forces, power and energy at every tick (the machine file's `dynamics:`):
  /// DIR/forces.csv and a "dynamics" block in the summary (src/dynamics, docs/dynamics.md).
  bool dynamics = false;
  /// With `dynamics`, also the elastic machine's response to the planned actuator motion (the struts'
  /// stiffness_N_mm; src/dynamics/run_elastic.hpp, docs/dynamics_elastic.md): DIR/response.csv and the lowest
  /// natural frequency and the largest dynamic tool error in the summary's dynamics block.
  bool elastic = false;
  /// The tool's deflection under `dynamics_load` with the struts as springs
  /// (src/stiffness/run_deflection.hpp, docs/stiffness.md): DIR/deflection.csv and a "stiffness" block in the
  /// summary.
  bool stiffness = false;
  /// The process load on the tool, for the dynamics (nullptr: gravity only) and the deflection.
  const statics::LoadModel* dynamics_load = nullptr;
  /// Told now and then how far the writing is and at which program line (core/progress.hpp).
  ProgressSink progress;
  /// What the interpreter noted about how it read the program (CanonicalProgram::notes): added to the
  /// summary's warnings.
  std::vector<std::string> program_notes;
  /// Where the moves of a calling line were written (pipeline::subroutine_lines): the summary's
  /// "subroutine_lines" when not empty.
  nlohmann::json subroutine_lines = nlohmann::json::object();
};

/// Streams the plan at the servo rate into the three files, staged in `outputs` (which must have its
/// directory); the caller commits the set, possibly with more files. Returns the measured summary.
Result<RunSummary> write_plan_outputs(const MotionPlan& plan, const Machine& machine, OutputSet& outputs,
                                      const OutputOptions& options);

/// The same into `directory` as a set of its own, committed on success.
Result<RunSummary> write_plan_outputs(const MotionPlan& plan, const Machine& machine,
                                      const std::string& directory, const OutputOptions& options);

/// The summary as JSON (units in the key names).
nlohmann::json summary_json(const MotionPlan& plan, const Machine& machine, const RunSummary& run);

}  // namespace pkm::planning
