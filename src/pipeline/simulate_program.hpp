#pragma once
// `pkm simulate PLAN_DIR` as one library call (docs/simulate.md): a planned run on the machine in
// simulation, the drives' servo loops closed on the elastic machine under the process load with the drives'
// imperfections (servo/machine_run.hpp). It gives the tool's actual path, the contour error at every servo
// tick and the program lines where it is largest, and splits the error into its causes by switching them on
// one at a time: the servo part (the loops on the rigid machine, ideal drives, no load), the elastic part
// (the elastic machine instead), the load part (the process load on it) and the drives' part (their
// friction, lost motion, encoder, delay and characteristic); the four parts add up to the whole error as
// vectors at every tick. Written, as one output set beside the plan or into --out: simulate.csv,
// simulate_summary.json and simulate.svg.
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/progress.hpp"
#include "core/result.hpp"
#include "machine/machine.hpp"
#include "servo/machine_run.hpp"
#include "statics/load_model.hpp"

namespace pkm::pipeline {

struct SimulateJob {
  std::string plan_directory;  ///< the output directory of pkm plan
  std::string out_directory;   ///< where to write ("": the plan directory)
  statics::LoadModel load;     ///< the process load along the program (none: empty)
  bool split = true;           ///< also the runs that split the error into its parts
  int inertia_stride = 10;     ///< the rigid plant's inertia every this many servo ticks
  std::string report_path;     ///< the plan's HTML report with the simulation's charts ("": none)
  servo::CoupledOptions coupled;
  ProgressSink progress;
  /// Also told every servo tick of the full machine's run (e.g. the circle test's measurement), from the
  /// thread running it.
  std::function<Status(const servo::MachineRunTick&)> listener;
};

/// One cause's share of the contour error, over the run.
struct ContourPart {
  const char* name = "";
  double max_mm = 0.0;
  double rms_mm = 0.0;
  int max_line = 0;
  double max_time_s = 0.0;
};

struct SimulateResult {
  long ticks = 0;
  double simulated_s = 0.0;
  ContourPart total{"total"};
  /// servo, elastic, load, drives (all zero when the job does not split).
  std::array<ContourPart, 4> parts{{{"servo"}, {"elastic"}, {"load"}, {"drives"}}};
  /// The program lines with the largest contour error, worst first (at most 10): line, error mm.
  std::vector<std::pair<int, double>> worst_lines;
  nlohmann::json json;  ///< simulate_summary.json as written
};

Result<SimulateResult> simulate_program(const Machine& machine, const SimulateJob& job);

}  // namespace pkm::pipeline
