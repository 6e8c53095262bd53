#pragma once
// Planning a part program on a machine: the path (path/path.hpp), the speed profile along it
// (speed_profile.hpp) within the programmed feeds, the path acceleration and jerk, and the actuators' own
// speed and acceleration limits, with every limit checked along the whole path (not only at block ends).
#include <optional>
#include <string>

#include "core/progress.hpp"
#include "core/result.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"
#include "path/path_builder.hpp"
#include "planning/speed_profile.hpp"
#include "program/canonical_program.hpp"

namespace pkm::planning {

struct PlanOptions {
  double rate_hz = 1000.0;                  ///< servo rate of the output
  double override_pct = 100.0;              ///< operator feed override, 0 < override ≤ 200 %
  std::optional<double> path_tolerance_mm;  ///< corner blending tolerance; default: the machine file's
  /// Fraction of the actuator speed and acceleration limits the plan may use: the rest absorbs the
  /// difference between the planning grid and the servo-rate samples.
  double actuator_limit_margin = 0.95;
  double sample_spacing_mm =
      1.0;  ///< largest distance between planning samples (mm, or deg when only rotating)
  double condition_check_spacing_mm = 2.0;  ///< conditioning (singularity) checks along the path
  /// False: no jerk limit (trapezoidal path speed, the linear acceleration law); the jerk filter shrinks to
  /// one period.
  bool jerk_limited = true;
  /// Bounds on the work a plan may take (the CLI's --max-ticks, --max-samples): a program whose motion would
  /// run longer, or whose path needs more planning samples, is refused up front at the line that crosses the
  /// bound, instead of filling the disk or the memory. The defaults allow a day of motion at 1 kHz: 86.4 M
  /// ticks, about 10 GB of CSV; and 50 M samples, a few GB of planning data.
  long max_ticks = 86'400'000;
  std::size_t max_samples = 50'000'000;
  /// The look-ahead window (lookahead_profile.hpp): the speeds are planned with at most this much path,
  /// this many moves and this many planning samples ahead of the last final speed. Where braking needs
  /// more, the window sets the speed (counted in PlanStatistics::lookahead_binding).
  double lookahead_mm = 5000.0;
  int lookahead_moves = 10000;
  std::size_t lookahead_samples = 262'144;
  ProgressSink progress;  ///< told how far the planning is, now and then (core/progress.hpp)
};

/// What the plan used and where it is limited; for the summary.
struct PlanStatistics {
  int blocks = 0;    ///< canonical moves (motion and dwell)
  int segments = 0;  ///< path segments, blends included
  int blends = 0;
  std::size_t samples = 0;
  double length_mm = 0.0;
  double filter_time_s = 0.0;  ///< moving-average window that limits the jerk
  double max_condition_number = 0.0;
  /// Fraction of the path length where the actuators, not the feed, set the speed cap.
  double actuator_limited_fraction = 0.0;
  /// Places where the look-ahead window was full before braking distance was found: the speed there is
  /// lower than the whole program's plan would give (0: the plan equals the whole program's).
  long lookahead_binding = 0;
};

struct MotionPlan {
  path::Path path;
  ProfileSamples samples;
  std::vector<int> sample_segment;  ///< segment of each sample
  TimedProfile timed;
  int filter_ticks = 1;  ///< N: moving average over N servo periods
  double period_s = 0.001;
  double path_tolerance_mm = 0.01;  ///< the corner-blending tolerance the path was built with
  double duration_s = 0.0;          ///< from the first tick to the last (the filtered motion)
  PlanStatistics statistics;
  std::string program_source;
};

/// Plans `program` on `machine`. Errors name the program line and the limit (file and line of the machine
/// file where it was set).
Result<MotionPlan> plan_motion(const Machine& machine, const program::CanonicalProgram& program,
                               const PlanOptions& options);

/// The InterpretOptions start for `machine`: its home, in program coordinates, with A B C of its rotation.
struct ProgramStart {
  Eigen::Vector3d start_mm;
  Eigen::Vector3d start_abc_deg;
};
ProgramStart program_start(const Machine& machine);

/// How program coordinates sit in `machine` (its program origin, home rotation, planar or not) for the path.
path::PathFrame program_frame(const Machine& machine);

}  // namespace pkm::planning
