#pragma once
// `pkm servo PLAN_DIR` as one library call (docs/servo.md): reads a planned run back from its ticks.h5 or CSV
// files (actuators: the set points; path: the commanded tool poses and their program lines), designs each
// drive's loops from the machine file's `servo:` section, refuses unstable loops, simulates all drives on the
// coupled plant, and writes servo.csv (per tick: following error, force and command per drive, contour error
// and lag), servo_bode.csv (each drive's loops, continuous and sampled) and servo_summary.json, as one output
// set, into the run's directory (or another).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "core/result.hpp"
#include "machine/machine.hpp"
#include "servo/loop_analysis.hpp"
#include "servo/servo_run.hpp"

namespace pkm::pipeline {

struct ServoJob {
  std::string plan_directory;  ///< the output directory of pkm plan
  std::string out_directory;   ///< where to write ("": the plan directory)
  bool coupled = true;         ///< false: each drive on its own inertia only (servo_run.hpp)
  int inertia_stride = 10;     ///< the plant's inertia is evaluated every this many servo ticks
  int bode_points = 120;
  std::string report_path;  ///< the HTML report of the run with the servo plots ("": none)
  ProgressSink progress;    ///< told the phase, how far the run is and its program line, now and then
  /// Also told every servo tick, after servo.csv (e.g. the circle test's measurement).
  std::function<Status(const servo::ServoTick&)> listener;
};

struct ServoProgramResult {
  servo::LoopDesign design;
  std::vector<servo::ChannelAnalysis> analysis;  ///< per drive
  servo::ServoSummary summary;
  nlohmann::json json;  ///< servo_summary.json as written
};

/// Reads the run of `job.plan_directory` back: set points, commanded poses, lines and the servo period.
/// Errors name the file, its line and column.
Result<servo::ServoRunInput> read_planned_run(const Machine& machine, const std::string& plan_directory);

/// What a run through the drives' loops starts from: the plan read back, the drives' loop steps per servo
/// period, the rigid plant along the run and the loops, tuned once for the inertia at the run's start (as a
/// drive is commissioned) and checked stable on the plant (coupled, or each drive on its own inertia).
struct PlannedServoRun {
  servo::ServoRunInput input;
  int steps_per_period = 1;
  servo::ServoPlant plant;
  servo::LoopDesign design;
};

/// Fails where the machine has no servo: section, the plan cannot be read or is not one plan's set, the loop
/// period does not divide the servo period, the plant cannot be evaluated or the loops are unstable.
Result<PlannedServoRun> prepare_planned_servo_run(const Machine& machine, const std::string& plan_directory,
                                                  int inertia_stride, bool coupled,
                                                  const ProgressSink& progress);

/// Whether two paths name the same folder (an output set joins its plan's folder then).
bool same_folder(const std::string& a, const std::string& b);

Result<ServoProgramResult> servo_program(const Machine& machine, const ServoJob& job);

}  // namespace pkm::pipeline
