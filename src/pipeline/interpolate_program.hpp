#pragma once
// `pkm interpolate` as one library call: a part program file in, planned at the servo period and turned into
// whole drive steps per period (Smirnov 2019), written as an output set: steps.csv and steps.bin (the drives'
// stream), contour.csv (per period: the contour error and where the tool is), summary.json and, if asked,
// the HTML report. The set replaces a previous run's only when all of it succeeded.
//
// Drive parameters the job leaves unset come from the machine file's `drives:` section, then from the
// defaults (1 ms, 0.001 mm per step, no step-rate limit).
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "interpolation/interpolate_run.hpp"
#include "interpolation/methods/feed_override.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"

namespace pkm::pipeline {

struct InterpolateJob {
  std::string program_path;                ///< G-code, or CL data (told apart by content)
  ProgramOptions program_options;          ///< tool table, subroutine path, parameter file
  std::optional<double> period_ms;         ///< servo period h, 0.1…20 ms
  std::optional<double> step;              ///< drive resolution Δ, mm per step (deg for angular actuators)
  std::optional<double> max_step_rate_hz;  ///< per drive
  double override_pct = 100.0;             ///< operator feed override at the start, % (> 0, ≤ 200)
  /// Override changes during the run, in % of the programmed feed (they act from period i+2).
  std::vector<interpolation::OverrideChange> override_changes;
  /// The acceleration law of the plan and of override changes: linear drops the jerk limit (trapezoidal).
  interpolation::RampShape accel = interpolation::RampShape::s_curve;
  /// Method, ρ_max, δρ_max, chord check, orientation criterion, error samples, estimating settings. Its
  /// period, step, step rate and feed override are set from the fields above.
  interpolation::InterpolateOptions options;
  ProgressSink progress;  ///< told the phase, how far it is and the program line, now and then
  /// Called at every period with its steps, its contour error and the path point (callers that keep the
  /// periods in memory: Python); the files are written as well when out_directory is given.
  std::function<void(const interpolation::StepPeriod&, const interpolation::PeriodContour&,
                     const Eigen::Vector3d& path_mm)>
      on_period;
  std::string out_directory;  ///< empty: no files (on_period is then the run's only output)
  std::string report_path;    ///< empty: no report (needs out_directory)
};

struct InterpolateProgramResult {
  interpolation::InterpolateSummary summary;
  int blocks = 0;       ///< of the program
  nlohmann::json json;  ///< summary.json as written
};

Result<InterpolateProgramResult> interpolate_program(const Machine& machine, const InterpolateJob& job);

}  // namespace pkm::pipeline
