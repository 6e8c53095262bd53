#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "machine/joint_limits.hpp"
#include "path/path_builder.hpp"
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
  return ok_status();
}

}  // namespace

Result<MotionPlan> plan_motion(const Machine& machine, const program::CanonicalProgram& program,
                               const PlanOptions& options) {
  if (Status status = check_options(options); !status) return status.error();
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
  auto sampled = sample_path(machine, program, plan.path, sampling, plan.samples, plan.sample_segment);
  if (!sampled) return sampled.error();

  erode_caps(plan.samples, window_s, 0.0);
  plan_speeds(plan.samples);
  plan.timed = time_profile(plan.samples);
  const long last_tick =
      static_cast<long>(std::ceil(plan.timed.end_time_s / plan.period_s)) + plan.filter_ticks - 1;
  plan.duration_s = static_cast<double>(last_tick) * plan.period_s;

  PlanStatistics& stats = plan.statistics;
  stats = sampled->statistics;
  stats.blocks = static_cast<int>(program.moves.size());
  stats.segments = static_cast<int>(plan.path.segments.size());
  stats.blends = static_cast<int>(plan.path.blend_tables.size());
  stats.samples = plan.samples.size();
  stats.length_mm = plan.path.length();
  stats.filter_time_s = window_s;
  return plan;
}

}  // namespace pkm::planning
