#include "planning/plan_producer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "path/path_appender.hpp"
#include "planning/commanded_coordinates.hpp"
#include "planning/lookahead_profile.hpp"
#include "planning/path_sampling.hpp"
#include "planning/workspace_excursion.hpp"

namespace pkm::planning {

namespace {

/// The window's arrays are compacted once this many samples (and at least half of them) lie behind.
constexpr std::size_t kReleaseAtLeast = 4096;

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

path::PathOptions path_options(const MotionSettings& motion, const PlanOptions& options) {
  path::PathOptions path_options;
  path_options.rapid_mm_s = motion.rapid_mm_min / 60.0;
  path_options.max_feed_mm_s = motion.max_feed_mm_min / 60.0;
  path_options.angular_feed_deg_s = motion.angular_feed_deg_min / 60.0;
  path_options.path_tolerance_mm = options.path_tolerance_mm.value_or(motion.path_tolerance_mm);
  return path_options;
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

SamplingSettings sampling_settings(const PlanOptions& options, const MotionPlan& plan, double window_s,
                                   int total_lines) {
  SamplingSettings sampling;
  sampling.override_factor = options.override_pct / 100.0;
  sampling.actuator_margin = options.actuator_limit_margin;
  sampling.spacing = options.sample_spacing_mm;
  sampling.condition_spacing = options.condition_check_spacing_mm;
  sampling.period_s = plan.period_s;
  sampling.stop_hold_s = window_s;
  sampling.chord_tolerance_mm = 0.1 * std::max(plan.path_tolerance_mm, 1e-3);
  sampling.max_samples = options.max_samples;
  sampling.total_lines = total_lines;
  sampling.progress = options.progress;
  return sampling;
}

template <class T>
void erase_front(std::vector<T>& values, std::size_t count) {
  values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(count));
}

}  // namespace

struct PlanProducer::Stages {
  CommandedCoordinateCheck commanded;
  path::PathAppender appender;
  PathSampler sampler;
  LookaheadProfile lookahead;
  path::PathFrame frame;  ///< for the whole path built again where a refusal lists every excursion
  path::PathOptions path_options;
};

PlanProducer::PlanProducer(const Machine& machine, const program::CanonicalProgram& program,
                           std::unique_ptr<MoveSource> moves, const PlanOptions& options, MotionPlan& plan)
    : machine_(machine), program_(program), moves_(std::move(moves)), options_(options), plan_(plan) {}

PlanProducer::~PlanProducer() = default;

Result<std::unique_ptr<PlanProducer>> PlanProducer::start(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          const PlanOptions& options, MotionPlan& plan) {
  return start(machine, program, std::make_unique<ProgramMoves>(program), options, plan);
}

Result<std::unique_ptr<PlanProducer>> PlanProducer::start(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          std::unique_ptr<MoveSource> moves,
                                                          const PlanOptions& options, MotionPlan& plan) {
  if (Status status = check_options(options); !status) return status.error();
  const MotionSettings& motion = machine.motion;
  plan = MotionPlan{};
  plan.program_source = program.source;
  plan.period_s = 1.0 / options.rate_hz;
  const path::PathOptions along = path_options(motion, options);
  plan.path_tolerance_mm = along.path_tolerance_mm;
  // Moving average of length T = 2·a/j keeps the path jerk within j (servo_stream.hpp).
  const double jerk = options.jerk_limited ? motion.path_jerk_mm_s3 : std::numeric_limits<double>::max();
  const double filter_time = 2.0 * motion.path_accel_mm_s2 / jerk;
  plan.filter_ticks = std::max(1, static_cast<int>(std::lround(filter_time * options.rate_hz)));
  const double window_s = plan.filter_ticks * plan.period_s;
  plan.statistics.filter_time_s = window_s;

  const int lines = moves->line_count();
  std::unique_ptr<PlanProducer> producer(new PlanProducer(machine, program, std::move(moves), options, plan));
  const path::PathFrame frame = program_frame(machine);
  const SamplingSettings sampling = sampling_settings(options, plan, window_s, lines);
  producer->stages_.reset(new Stages{CommandedCoordinateCheck(machine, program),
                                     path::PathAppender(program.source, program, frame, along, plan.path),
                                     PathSampler(machine, program.source, plan.path, sampling),
                                     LookaheadProfile(lookahead_settings(options, motion, window_s)), frame,
                                     along});
  producer->tick_bound_s_ = static_cast<double>(options.max_ticks) * plan.period_s;
  report_progress(options.progress, "planning", 0.0);
  return producer;
}

Status PlanProducer::extend_to(double time_s) {
  while (!finished_ && (plan_.timed.time_s.empty() || plan_.timed.time_s.back() <= time_s)) {
    if (Status pumped = pump(); !pumped) return pumped;
  }
  return ok_status();
}

Status PlanProducer::run_to_end(bool keep_whole) {
  while (!finished_) {
    if (Status pumped = pump(); !pumped) return pumped;
    if (!keep_whole && !plan_.samples.s.empty())
      release(plan_.samples.first + plan_.samples.size() - 1, plan_.sample_segment.back());
  }
  return ok_status();
}

Status PlanProducer::pump() {
  const auto started = std::chrono::steady_clock::now();
  Status pumped = pump_one_move();
  planning_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return pumped;
}

Status PlanProducer::pump_one_move() {
  Stages& stages = *stages_;
  auto move = moves_->next();
  if (!move) return move.error();
  const bool at_end = *move == nullptr;
  if (!at_end) {
    if (Status allowed = stages.commanded.add(**move); !allowed) return allowed;
    if (Status added = stages.appender.add(**move, next_move_); !added) return added;
    ++next_move_;
  } else {
    stages.appender.finish();
    if (plan_.path.segment_end() == 0) {
      return Error{ErrorCode::bad_input,
                   fmt::format("{}: the program moves nothing; there is no motion to plan", program_.source)};
    }
  }
  Status sampled = stages.sampler.add_segments(plan_.path.segment_end());
  if (sampled && at_end) sampled = stages.sampler.finish();
  if (!sampled) return refuse(sampled.error());
  for (const SampledPoint& point : stages.sampler.ready()) {
    stages.lookahead.push(point.raw);
    waiting_segment_.push_back(point.segment);
  }
  stages.sampler.clear_ready();
  if (at_end) stages.lookahead.finish();
  take_planned();
  if (at_end) return finish_plan();
  // Past the bound on the ticks: refused now, before the ticks reach it, with the whole motion's length
  // (planned on, without keeping it).
  if (crossing_line_ != 0 && !measuring_length_) {
    measuring_length_ = true;
    if (Status measured = run_to_end(false); !measured) return measured;
    return too_many_ticks();  // finish_plan refuses it first: the bound is crossed
  }
  return ok_status();
}

/// Out of reach or past a position limit: the first sample's error, then the whole extent of the program's
/// excursions (the user moving the part needs all of it), from the whole path built again for the scan.
Error PlanProducer::refuse(const Error& first) const {
  if (!stages_->sampler.failed_in_workspace()) return first;
  auto program = moves_->whole();
  if (!program) return first;
  auto whole = path::build_path(*program, stages_->frame, stages_->path_options);
  if (!whole) return first;
  std::vector<double> s;
  std::vector<int> segment;
  whole_path_samples(*whole, options_.sample_spacing_mm, options_.max_samples, s, segment);
  const WorkspaceExcursions found = find_excursions(machine_, *whole, s, segment);
  if (found.excursions.empty()) return first;  // e.g. the conditioning limit: not a place to move away from
  Error refused = first;
  refused.message += "; " + describe_excursions(found);
  refused.details_json = excursions_json(found);
  return refused;
}

void PlanProducer::take_planned() {
  LookaheadProfile& lookahead = stages_->lookahead;
  for (const PlannedSample& sample : lookahead.planned()) {
    append_sample(sample, waiting_segment_.front());
    waiting_segment_.pop_front();
  }
  lookahead.clear_planned();
  peak_samples_ = std::max(peak_samples_, plan_.samples.size());
  peak_segments_ = std::max(peak_segments_, plan_.path.segments.size());
}

/// The sample's arrival: after the previous one's hold, with constant acceleration between their speeds
/// (time_profile, speed_profile.hpp, in the same order of operations).
void PlanProducer::append_sample(const PlannedSample& sample, int segment) {
  ProfileSamples& samples = plan_.samples;
  const bool first = samples.first + samples.size() == 0;
  const double previous_time_s = first ? 0.0 : plan_.timed.time_s.back();
  if (!first) {
    const double v_sum = samples.speed.back() + sample.speed;
    if (v_sum > 0.0) clock_s_ += 2.0 * (sample.s - samples.s.back()) / v_sum;
  }
  const int line = plan_.path.segment(segment).line;
  if (!first && clock_s_ - previous_time_s > slowest_s_) {
    slowest_s_ = clock_s_ - previous_time_s;
    slowest_line_ = line;
  }
  if (crossing_line_ == 0 && clock_s_ > tick_bound_s_) crossing_line_ = line;
  last_line_ = line;
  samples.s.push_back(sample.s);
  samples.speed_cap.push_back(sample.speed_cap);
  samples.accel_cap.push_back(sample.accel_cap);
  samples.speed.push_back(sample.speed);
  samples.hold_s.push_back(sample.hold_s);
  samples.stop.push_back(sample.stop ? 1 : 0);
  plan_.sample_segment.push_back(segment);
  plan_.timed.time_s.push_back(clock_s_);
  clock_s_ += sample.hold_s;
}

/// The refusal of a plan longer than `max_ticks`: at the line where the motion crosses the bound, naming the
/// block that takes longest (a feed of 1e-6 mm/min, a machine's feed cap of 1e-9) and how long it takes.
Error PlanProducer::too_many_ticks() const {
  const int line = crossing_line_ != 0 ? crossing_line_ : last_line_;
  return Error{
      ErrorCode::limit_exceeded,
      fmt::format("{}:{}: the motion would take {:.4g} s ({:.4g} ticks at {:g} Hz) and passes the bound "
                  "of {} ticks here; the slowest stretch is at line {} ({:.4g} s between two planning "
                  "samples: check its feed and the machine's feed limits); raise --max-ticks to plan it",
                  plan_.program_source, line, plan_.duration_s, plan_.duration_s / plan_.period_s,
                  1.0 / plan_.period_s, options_.max_ticks, slowest_line_ != 0 ? slowest_line_ : line,
                  slowest_s_),
      ErrorLocation{plan_.program_source, line, 0, ""}};
}

Status PlanProducer::finish_plan() {
  finished_ = true;
  plan_.timed.end_time_s = clock_s_;
  // In double first: a motion of 1e15 s must be refused, not overflow a long.
  const double ticks = std::ceil(plan_.timed.end_time_s / plan_.period_s) + plan_.filter_ticks - 1;
  plan_.duration_s = ticks * plan_.period_s;
  if (ticks > static_cast<double>(options_.max_ticks)) return too_many_ticks();
  const Stages& stages = *stages_;
  PlanStatistics& stats = plan_.statistics;
  stats.blocks = next_move_;
  stats.segments = plan_.path.segment_end();
  stats.blends = stages.appender.blends();
  stats.samples = stages.sampler.sample_count();
  stats.length_mm = plan_.path.length();
  stats.max_condition_number = stages.sampler.max_condition_number();
  stats.actuator_limited_fraction =
      stats.length_mm > 0 ? stages.sampler.actuator_limited_length() / stats.length_mm : 0.0;
  stats.lookahead_binding = stages.lookahead.binding_count();
  return ok_status();
}

void PlanProducer::release(std::size_t sample, int segment) {
  ProfileSamples& samples = plan_.samples;
  if (samples.size() > 0) {
    // The last sample stays: the next one's arrival is timed from it.
    const std::size_t keep_from = std::min(sample, samples.first + samples.size() - 1);
    const std::size_t drop = keep_from > samples.first ? keep_from - samples.first : 0;
    if (drop >= kReleaseAtLeast && 2 * drop >= samples.size()) {
      samples.erase_front(drop);
      erase_front(plan_.sample_segment, drop);
      erase_front(plan_.timed.time_s, drop);
    }
  }
  int keep_segment = std::min(segment, stages_->sampler.first_needed_segment());
  if (!waiting_segment_.empty()) keep_segment = std::min(keep_segment, waiting_segment_.front());
  plan_.path.drop_before(keep_segment);
}

Result<std::unique_ptr<StreamedPlan>> start_streamed_plan(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          const PlanOptions& options) {
  const MoveSourceFactory whole = [&program]() -> Result<std::unique_ptr<MoveSource>> {
    return std::unique_ptr<MoveSource>(std::make_unique<ProgramMoves>(program));
  };
  return start_streamed_plan(machine, program, whole, options);
}

Result<std::unique_ptr<StreamedPlan>> start_streamed_plan(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          const MoveSourceFactory& moves,
                                                          const PlanOptions& options) {
  auto streamed = std::make_unique<StreamedPlan>();
  auto reader = moves();
  if (!reader) return reader.error();
  PlanOptions quiet = options;
  quiet.progress = nullptr;  // the stream tells its own progress
  auto source = PlanProducer::start(machine, program, std::move(*reader), quiet, streamed->plan);
  if (!source) return source.error();
  streamed->source = std::move(*source);
  return streamed;
}

}  // namespace pkm::planning
