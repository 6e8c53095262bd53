#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "machine/joint_limits.hpp"
#include "path/path_builder.hpp"
#include "planning/commanded_coordinates.hpp"
#include "planning/lookahead_profile.hpp"
#include "planning/motion_plan.hpp"
#include "planning/path_sampling.hpp"

namespace pkm::planning {

ProgramStart program_start(const Machine& machine) {
  const Pose& home = machine.mechanism->home();
  ProgramStart start;
  start.start_mm = home.position_mm - machine.motion.program_origin_mm;
  start.start_abc_deg = angles_from_rotation(AngleConvention::abc, home.rotation) * (180.0 / kPi);
  if (machine.mechanism->is_planar()) start.start_abc_deg.head<2>().setZero();
  return start;
}

namespace {

Status check_options(const PlanOptions& options) {
  // The library speaks of its parameters; the CLI names its flags before a value gets here.
  if (!(options.rate_hz >= 1.0 && options.rate_hz <= 100000.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("servo rate: must be ≥ 1 and ≤ 100000 Hz, got {} Hz", options.rate_hz));
  }
  if (!(options.override_pct > 0.0 && options.override_pct <= 200.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("feed override: must be > 0 and ≤ 200 %, got {} %", options.override_pct));
  }
  if (options.path_tolerance_mm &&
      !(*options.path_tolerance_mm >= 0.0 && std::isfinite(*options.path_tolerance_mm))) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("path tolerance: must be 0 (exact stops) or a positive distance in mm, got {}",
                    *options.path_tolerance_mm));
  }
  if (!(options.lookahead_mm > 0.0) || options.lookahead_moves < 1 || options.lookahead_samples < 2) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("look-ahead window: needs a length > 0 mm, at least 1 move and 2 samples, got "
                    "{} mm, {} moves, {} samples",
                    options.lookahead_mm, options.lookahead_moves, options.lookahead_samples));
  }
  return ok_status();
}

/// The refusal of a plan longer than `max_ticks`: at the line where the motion crosses the bound, naming the
/// block that takes longest (a feed of 1e-6 mm/min, a machine's feed cap of 1e-9) and how long it takes.
Error too_many_ticks(const MotionPlan& plan, long max_ticks) {
  const std::vector<double>& time_s = plan.timed.time_s;
  const double bound_s = static_cast<double>(max_ticks) * plan.period_s;
  const auto crossing = std::upper_bound(time_s.begin(), time_s.end(), bound_s);
  const std::size_t at = std::min<std::size_t>(crossing - time_s.begin(), time_s.size() - 1);
  const int line = plan.path.segments[plan.sample_segment[at]].line;
  double longest_s = 0.0;
  int longest_line = line;
  for (std::size_t i = 1; i < time_s.size(); ++i) {
    if (time_s[i] - time_s[i - 1] <= longest_s) continue;
    longest_s = time_s[i] - time_s[i - 1];
    longest_line = plan.path.segments[plan.sample_segment[i]].line;
  }
  return Error{
      ErrorCode::limit_exceeded,
      fmt::format("{}:{}: the motion would take {:.4g} s ({:.4g} ticks at {:g} Hz) and passes the bound "
                  "of {} ticks here; the slowest stretch is at line {} ({:.4g} s between two planning "
                  "samples: check its feed and the machine's feed limits); raise --max-ticks to plan it",
                  plan.program_source, line, plan.duration_s, plan.duration_s / plan.period_s,
                  1.0 / plan.period_s, max_ticks, longest_line, longest_s),
      ErrorLocation{plan.program_source, line, 0, ""}};
}

/// The look-ahead window of `options` for the filter window T: no cap is above the machine's fastest speed.
LookaheadSettings lookahead_settings(const PlanOptions& options, const MotionSettings& motion,
                                     double window_s) {
  LookaheadSettings settings;
  settings.filter_window_s = window_s;
  settings.fastest_cap =
      std::max({motion.rapid_mm_min, motion.max_feed_mm_min, motion.angular_feed_deg_min}) / 60.0;
  settings.max_length = options.lookahead_mm;
  settings.max_moves = options.lookahead_moves;
  settings.max_samples = options.lookahead_samples;
  return settings;
}

}  // namespace

Result<MotionPlan> plan_motion(const Machine& machine, const program::CanonicalProgram& program,
                               const PlanOptions& options) {
  if (Status status = check_options(options); !status) return status.error();
  if (Status commanded = check_commanded_coordinates(machine, program); !commanded) return commanded.error();
  const MotionSettings& motion = machine.motion;
  path::PathFrame frame;
  frame.program_origin_mm = motion.program_origin_mm;
  frame.reference_rotation = Eigen::Quaterniond(machine.mechanism->home().rotation);
  frame.planar = machine.mechanism->is_planar();
  path::PathOptions path_options;
  path_options.rapid_mm_s = motion.rapid_mm_min / 60.0;
  path_options.max_feed_mm_s = motion.max_feed_mm_min / 60.0;
  path_options.angular_feed_deg_s = motion.angular_feed_deg_min / 60.0;
  path_options.path_tolerance_mm = options.path_tolerance_mm.value_or(motion.path_tolerance_mm);
  report_progress(options.progress, "building the tool path");
  auto built = path::build_path(program, frame, path_options);
  if (!built) return built.error();
  if (built->segments.empty()) {
    return Error{ErrorCode::bad_input,
                 fmt::format("{}: the program moves nothing; there is no motion to plan", program.source)};
  }

  MotionPlan plan;
  plan.program_source = program.source;
  plan.path = std::move(*built);
  plan.period_s = 1.0 / options.rate_hz;
  plan.path_tolerance_mm = path_options.path_tolerance_mm;
  // Moving average of length T = 2·a/j keeps the path jerk within j (servo_stream.hpp).
  const double jerk = options.jerk_limited ? motion.path_jerk_mm_s3 : std::numeric_limits<double>::max();
  const double filter_time = 2.0 * motion.path_accel_mm_s2 / jerk;
  plan.filter_ticks = std::max(1, static_cast<int>(std::lround(filter_time * options.rate_hz)));
  const double window_s = plan.filter_ticks * plan.period_s;

  SamplingSettings sampling;
  sampling.override_factor = options.override_pct / 100.0;
  sampling.actuator_margin = options.actuator_limit_margin;
  sampling.spacing = options.sample_spacing_mm;
  sampling.condition_spacing = options.condition_check_spacing_mm;
  sampling.period_s = plan.period_s;
  sampling.stop_hold_s = window_s;
  sampling.chord_tolerance_mm = 0.1 * std::max(path_options.path_tolerance_mm, 1e-3);
  sampling.max_samples = options.max_samples;
  sampling.progress = options.progress;
  auto sampled = sample_path(machine, program, plan.path, sampling, plan.samples, plan.sample_segment);
  if (!sampled) return sampled.error();

  report_progress(options.progress, "timing the motion");
  std::vector<int> sample_move(plan.samples.size());
  for (std::size_t i = 0; i < sample_move.size(); ++i)
    sample_move[i] = plan.path.segments[plan.sample_segment[i]].move;
  const long binding =
      plan_speeds_lookahead(plan.samples, sample_move, lookahead_settings(options, motion, window_s));
  plan.timed = time_profile(plan.samples);
  // In double first: a motion of 1e15 s must be refused, not overflow a long.
  const double ticks = std::ceil(plan.timed.end_time_s / plan.period_s) + plan.filter_ticks - 1;
  const long last_tick =
      ticks > static_cast<double>(options.max_ticks) ? options.max_ticks + 1 : static_cast<long>(ticks);
  plan.duration_s = ticks * plan.period_s;
  if (last_tick > options.max_ticks) return too_many_ticks(plan, options.max_ticks);

  PlanStatistics& stats = plan.statistics;
  stats = sampled->statistics;
  stats.blocks = static_cast<int>(program.moves.size());
  stats.segments = static_cast<int>(plan.path.segments.size());
  stats.blends = static_cast<int>(plan.path.blend_tables.size());
  stats.samples = plan.samples.size();
  stats.length_mm = plan.path.length();
  stats.filter_time_s = window_s;
  stats.lookahead_binding = binding;
  return plan;
}

}  // namespace pkm::planning
