#include "interpolation/interpolate_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/units.hpp"
#include "interpolation/error_amplification_scan.hpp"
#include "interpolation/plan_window_feed.hpp"
#include "interpolation/quantisation/remainder_quantizer.hpp"

namespace pkm::interpolation {

std::optional<Method> method_from_string(std::string_view name) {
  if (name == "exact") return Method::exact;
  if (name == "carrier") return Method::carrier;
  if (name == "carrier-corrected") return Method::carrier_corrected;
  if (name == "estimating") return Method::estimating;
  return std::nullopt;
}

std::string_view to_string(Method method) {
  switch (method) {
    case Method::exact:
      return "exact";
    case Method::carrier:
      return "carrier";
    case Method::carrier_corrected:
      return "carrier-corrected";
    case Method::estimating:
      return "estimating";
  }
  return "exact";
}

namespace {

using Clock = std::chrono::steady_clock;

Status check_interpolate_options(const InterpolateOptions& options, bool has_sinks) {
  // Smirnov 2019's carrier frequencies are 100 Hz … 10 kHz (§5.1); its simulations ran h = 20 ms (§5.2.3).
  if (!(options.period_s >= 1e-4 - 1e-12 && options.period_s <= 2e-2 + 1e-12)) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("servo period {} ms is outside 0.1…20 ms (carrier frequencies 50 Hz…10 kHz)",
                    options.period_s * 1e3));
  }
  if (!(options.step_mm >= 0.0) || (options.step_mm == 0.0 && has_sinks)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("drive step {} must be a positive drive resolution", options.step_mm));
  }
  if (options.step_mm == 0.0 && options.method != Method::exact && options.method != Method::carrier) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("the {} method needs whole drive steps (drive step > 0)", to_string(options.method)));
  }
  if (!(options.rho_max_mm >= kMinContourToleranceMm)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("contour tolerance ρ_max {} mm must be at least {} mm: below it the strut "
                                  "tolerance asks for more periods than any drive resolves",
                                  options.rho_max_mm, kMinContourToleranceMm));
  }
  if (options.delta_rho_max && !(*options.delta_rho_max > 0.0)) {
    return make_error(ErrorCode::bad_input, "error amplification limit δρ_max must be positive");
  }
  if (options.max_step_rate_hz && !(*options.max_step_rate_hz * options.period_s >= 2.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("largest step rate {} Hz allows fewer than 2 steps per {} ms period",
                                  *options.max_step_rate_hz, options.period_s * 1e3));
  }
  return ok_status();
}

int line_at(const path::Path& path, double s, int& hint) {
  if (path.segments.empty()) return 0;
  hint = path.find_segment(s, hint);
  return path.segment(hint).line;
}

// Per-period bookkeeping shared by the methods: sinks, step counts, compute time, progress.
class RunRecorder {
 public:
  RunRecorder(const std::vector<StepSink*>& sinks, InterpolateSummary& summary,
              const InterpolateOptions& options, double duration_s)
      : sinks_(sinks), summary_(summary), options_(options), duration_s_(duration_s) {}

  Status emit(const StepPeriod& period) {
    for (int j = 0; j < summary_.actuators; ++j) {
      const int steps = std::abs(period.steps[j]);
      if (steps > summary_.max_steps_per_period) {
        summary_.max_steps_per_period = steps;
        summary_.max_steps_line = period.line;
      }
    }
    for (StepSink* sink : sinks_) {
      if (Status written = sink->write(period); !written) return written;
    }
    if (options_.progress && period.index % 4096 == 0 && duration_s_ > 0.0) {
      report_progress(options_.progress, "interpolating", std::min(1.0, period.time_s / duration_s_),
                      period.line);
    }
    return ok_status();
  }
  void compute_time(Clock::time_point started) noexcept {
    period_time_.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
  }
  Status finish() {
    summary_.period_time = period_time_.distribution();
    summary_.max_compute_us_per_period = summary_.period_time.max_us;
    summary_.mean_compute_us_per_period = summary_.period_time.mean_us;
    for (StepSink* sink : sinks_) {
      if (Status done = sink->finish(); !done) return done;
    }
    report_progress(options_.progress, "interpolating", 1.0);
    return ok_status();
  }

 private:
  const std::vector<StepSink*>& sinks_;
  InterpolateSummary& summary_;
  const InterpolateOptions& options_;
  double duration_s_;
  DurationHistogram period_time_{kPeriodTimeBudgetNs};  // fixed buckets: recording never allocates
};

std::array<double, kMaxActuators> values_of(const std::array<std::int64_t, kMaxActuators>& steps, int count,
                                            double step) {
  std::array<double, kMaxActuators> values{};
  for (int j = 0; j < count; ++j) values[j] = static_cast<double>(steps[j]) * step;
  return values;
}

// One period computed on copies of the interpolator and the quantiser and thrown away, before the timed loop.
// The first period otherwise paid for first touches (13–23 µs instead of 4 on the ch5 line): code
// pages faulted in, the dynamic linker binding libm's functions on their first call, cold caches over the
// strut laws and the path. The copies leave the run's own state, statistics and FK history untouched.
void warm_up_period(const CarrierInterpolator& carrier, const DiscretenessCorrector* corrector,
                    const RemainderQuantizer* remainder) {
  CarrierInterpolator carrier_copy = carrier;
  CarrierPeriod period;
  if (!carrier_copy.next(period)) return;
  StepPeriod out;
  if (corrector) {
    DiscretenessCorrector corrector_copy = *corrector;
    (void)corrector_copy.quantize(period, out);
  } else if (remainder) {
    RemainderQuantizer remainder_copy = *remainder;
    remainder_copy.quantize(period, out);
  }
}

// The carrier's settings: the period, the chord check, the struts' tolerance, the feed override and each
// drive's largest increment per period (its speed limit, and the step rate less one step for the rounding).
CarrierSettings carrier_settings_for(const Machine& machine, const InterpolateOptions& options, double step,
                                     const InterpolateSummary& summary) {
  CarrierSettings settings;
  settings.period_s = options.period_s;
  settings.chord_check = options.chord_check;
  settings.strut_tolerance = summary.strut_tolerance;
  settings.feed_override = options.feed_override;
  for (int j = 0; j < summary.actuators; ++j) {
    double allowed = 0.0;
    if (machine.limits.speed) allowed = *machine.limits.speed * options.period_s;
    if (options.max_step_rate_hz && step > 0.0) {
      const double by_rate = (std::floor(*options.max_step_rate_hz * options.period_s) - 1.0) * step;
      allowed = allowed > 0.0 ? std::min(allowed, by_rate) : by_rate;
    }
    settings.max_increment[j] = allowed;
  }
  return settings;
}

// The strut laws of a whole path, fitted (or exact) within the run's strut tolerance.
Result<StrutLaws> whole_laws(const Machine& machine, const path::Path& path,
                             const InterpolateOptions& options, const InterpolateSummary& summary,
                             const std::string& source) {
  return options.method == Method::exact
             ? StrutLaws::exact(machine, path, source)
             : StrutLaws::fit(machine, path, LawFitSettings{.tolerance = 0.1 * summary.strut_tolerance},
                              source);
}

// How far ahead of the interpolator's ideal time a streamed plan's window reaches: a second of the motion, at
// least 100 periods, times the largest feed override (the ideal time advances by the override per period).
double window_lead_s(const InterpolateOptions& options) {
  double largest = std::max(1.0, options.feed_override.initial_percent / 100.0);
  for (const OverrideChange& change : options.feed_override.changes)
    largest = std::max(largest, change.percent / 100.0);
  return std::max(1.0, 100.0 * options.period_s) * largest;
}

// What a carrier run measured, into its summary.
void summarise_carrier_run(const CarrierInterpolator& carrier, const ContourMonitor& monitor,
                           const DiscretenessCorrector& corrector, const RemainderQuantizer& remainder,
                           bool corrected, InterpolateSummary& summary) {
  summary.carrier = carrier.statistics();
  summary.periods = summary.carrier.periods;
  summary.ideal_time_s = summary.carrier.ideal_time_s;
  summary.real_time_s = summary.carrier.real_time_s;
  summary.contour = monitor.statistics();
  summary.corrector = corrector.statistics();
  summary.max_remainder_steps = remainder.max_remainder_steps();
  summary.end_position = corrected ? corrector.position() : remainder.position();
  if (summary.periods > 0 && corrected) {
    const double periods = static_cast<double>(summary.periods);
    summary.fk_solves_per_period = static_cast<double>(summary.corrector.fk_solves) / periods;
    summary.jacobians_per_period = static_cast<double>(summary.corrector.jacobians) / periods;
  }
}

// The carrier methods along `path` with `laws` and `timing`; with a `feed`, those are the windows of a plan
// made while it streams, kept ahead of the interpolator and released behind it.
Status run_carrier(const Machine& machine, const path::Path& path, const IdealTiming& timing,
                   const StrutLaws& laws, PlanWindowFeed* feed, const InterpolateOptions& options,
                   double step, InterpolateSummary& summary, RunRecorder& recorder,
                   const std::string& source) {
  const int n = summary.actuators;
  const double lead_s = window_lead_s(options);
  if (feed != nullptr) {
    if (Status reached = feed->advance(0.0, lead_s); !reached) return reached;
  }
  CarrierInterpolator carrier(laws, timing, carrier_settings_for(machine, options, step, summary));
  std::array<double, kMaxActuators> ideal_start{};
  if (Status started = carrier.start(ideal_start); !started) {
    return Error{started.error().code, fmt::format("{}: {}", source, started.error().message)};
  }
  summary.ideal_start = ideal_start;

  const ContourGauge gauge(machine, path);
  ContourMonitor monitor(machine, path, gauge, options.error_samples);
  const bool corrected = options.method == Method::carrier_corrected;
  RemainderQuantizer remainder(n, step > 0.0 ? step : 1.0);
  CorrectorSettings corrector_settings;
  corrector_settings.step = step;
  corrector_settings.rho_max_mm = options.rho_max_mm;
  corrector_settings.orientation_criterion = options.orientation_criterion;
  corrector_settings.linearise = options.linearise;
  DiscretenessCorrector corrector(machine, path, gauge, corrector_settings);
  std::array<double, kMaxActuators> actual{};
  if (step > 0.0) {
    if (corrected) {
      if (Status started = corrector.start(ideal_start); !started) return started;
      summary.start_position = corrector.position();
    } else {
      remainder.start(ideal_start);
      summary.start_position = remainder.position();
    }
    actual = values_of(summary.start_position, n, step);
  } else {
    actual = ideal_start;
  }
  monitor.start(actual, timing.s_at(0.0));

  warm_up_period(carrier, step > 0.0 && corrected ? &corrector : nullptr, step > 0.0 ? &remainder : nullptr);
  CarrierPeriod period;
  StepPeriod out;
  int hint = 0;
  int trace_hint = 0;
  for (;;) {
    if (feed != nullptr) {
      if (Status reached = feed->advance(period.tau_end_s, lead_s); !reached) return reached;
    }
    const auto started = Clock::now();
    if (!carrier.next(period)) break;
    if (step > 0.0) {
      if (corrected) {
        if (Status chosen = corrector.quantize(period, out); !chosen) {
          return Error{chosen.error().code,
                       fmt::format("{}:{}: {}", source, laws.line(period.hint), chosen.error().message)};
        }
      } else {
        remainder.quantize(period, out);
      }
      actual = values_of(out.position, n, step);
      for (int j = 0; j < n; ++j) out.ideal_steps[j] = period.target[j] / step;
    } else {
      actual = period.target;
    }
    recorder.compute_time(started);
    out.index = period.index;
    out.time_s = period.time_s;
    out.line = line_at(path, period.s_end, hint);
    monitor.add(actual, period.s_start, period.s_end, period.time_s, options.period_s, out.line, period.last);
    if (options.on_period) {
      options.on_period(out, monitor.last_period(), path.evaluate(period.s_end, trace_hint).position_mm);
    }
    if (step > 0.0) {
      if (Status emitted = recorder.emit(out); !emitted) return emitted;
    }
    summary.ideal_end = period.target;
    if (feed != nullptr) feed->release_behind(period.s_start, period.tau_start_s);
  }
  summary.laws = laws.report();
  if (carrier.error()) {
    return Error{carrier.error()->code, fmt::format("{}:{}", source, carrier.error()->message)};
  }
  summarise_carrier_run(carrier, monitor, corrector, remainder, corrected, summary);
  return ok_status();
}

Status run_estimating(const Machine& machine, const path::Path& path, const IdealTiming& timing,
                      const InterpolateOptions& options, double step, InterpolateSummary& summary,
                      RunRecorder& recorder, const std::string& source) {
  const int n = summary.actuators;
  EstimatingSettings settings = options.estimating;
  settings.step_mm = step;
  EstimatingInterpolator estimator(machine, path, settings, source);
  if (Status started = estimator.start(); !started) return started;
  summary.start_position = estimator.position_steps();
  const ContourGauge gauge(machine, path);
  ContourMonitor monitor(machine, path, gauge, options.error_samples);
  monitor.start(values_of(summary.start_position, n, step), timing.s_at(0.0));
  FeedOverride feed(options.feed_override, options.period_s);
  double tau = 0.0;
  double s_reached = timing.s_at(0.0);
  bool more = true;
  Tact tact;
  StepPeriod out;
  int hint = 0;
  int trace_hint = 0;
  for (long index = 0; more; ++index) {
    const auto started = Clock::now();
    tau = std::min(timing.duration_s(), tau + feed.factor(index) * options.period_s);
    const bool final_period = tau >= timing.duration_s();
    const double s_target = timing.s_at(tau);
    const std::array<std::int64_t, kMaxActuators> before = estimator.position_steps();
    const double s_before = s_reached;
    // The tacts that bring the tool up to this period's ideal point (all of them in the last period).
    while (final_period || s_reached < s_target) {
      if (!estimator.next(tact)) {
        more = false;
        break;
      }
      s_reached = tact.s;
    }
    if (estimator.error()) return *estimator.error();
    recorder.compute_time(started);
    out.index = index;
    out.time_s = static_cast<double>(index + 1) * options.period_s;
    out.line = line_at(path, s_reached, hint);
    for (int j = 0; j < n; ++j) {
      out.position[j] = estimator.position_steps()[j];
      out.steps[j] = static_cast<std::int32_t>(out.position[j] - before[j]);
      out.ideal_steps[j] = static_cast<double>(out.position[j]);
    }
    monitor.add(values_of(out.position, n, step), s_before, s_reached, out.time_s, options.period_s, out.line,
                !more);
    if (options.on_period) {
      options.on_period(out, monitor.last_period(), path.evaluate(s_reached, trace_hint).position_mm);
    }
    if (Status emitted = recorder.emit(out); !emitted) return emitted;
    summary.periods = index + 1;
    if (index > 100'000'000)
      return make_error(ErrorCode::limit_exceeded, "the estimating method does not end");
  }
  summary.estimating = estimator.statistics();
  summary.end_position = estimator.position_steps();
  summary.ideal_time_s = timing.duration_s();
  summary.real_time_s = static_cast<double>(summary.periods) * options.period_s;
  summary.contour = monitor.statistics();
  if (summary.periods > 0) {
    summary.fk_solves_per_period =
        static_cast<double>(summary.estimating.fk_solves) / static_cast<double>(summary.periods);
  }
  return ok_status();
}

}  // namespace

namespace {

// The summary's settings, δρ_max (given, or the path's) and the strut tolerance of eq. 155.
InterpolateSummary summary_before_run(const Machine& machine, const InterpolateOptions& options,
                                      const ErrorAmplification& amplification) {
  InterpolateSummary summary;
  summary.method = options.method;
  summary.period_s = options.period_s;
  summary.step_mm = options.step_mm;
  summary.rho_max_mm = options.rho_max_mm;
  summary.actuators = machine.mechanism->actuator_count();
  if (options.delta_rho_max) {
    summary.delta_rho_max = *options.delta_rho_max;
  } else {
    summary.delta_rho_max = amplification.largest;
    summary.delta_rho_max_line = amplification.line;
  }
  // eq. 155: 10 % of the budget is kept for the strut laws' own approximation error.
  summary.strut_tolerance = 0.9 * options.rho_max_mm / summary.delta_rho_max;
  return summary;
}

// Angular actuators take their step in degrees on the command line; inside, radians.
double actuator_step(const Machine& machine, const InterpolateOptions& options) {
  return machine.mechanism->actuators_are_angles() ? rad_from_deg(options.step_mm) : options.step_mm;
}

}  // namespace

Result<InterpolateSummary> interpolate(const Machine& machine, const path::Path& path,
                                       const IdealTiming& timing, const InterpolateOptions& options,
                                       const std::vector<StepSink*>& sinks, const std::string& source) {
  if (Status valid = check_interpolate_options(options, !sinks.empty()); !valid) return valid.error();
  ErrorAmplificationScan scan(machine, options.amplification_spacing, source);
  if (!options.delta_rho_max) {
    for (int k = 0; k < path.segment_end(); ++k) {
      if (Status sampled = scan.add_segment(path, k); !sampled) return sampled.error();
    }
    if (Status finished = scan.finish(path); !finished) return finished.error();
  }
  InterpolateSummary summary = summary_before_run(machine, options, scan.result());
  const double step = actuator_step(machine, options);
  RunRecorder recorder(sinks, summary, options, timing.duration_s());
  Status ran = ok_status();
  if (options.method == Method::estimating) {
    ran = run_estimating(machine, path, timing, options, step, summary, recorder, source);
  } else {
    auto laws = whole_laws(machine, path, options, summary, source);
    if (!laws) return laws.error();
    ran = run_carrier(machine, path, timing, *laws, nullptr, options, step, summary, recorder, source);
  }
  if (!ran) return ran.error();
  if (Status finished = recorder.finish(); !finished) return finished.error();
  return summary;
}

Result<StreamedPlanCheck> check_streamed_plan(const Machine& machine, planning::StreamedPlan& streamed,
                                              double amplification_spacing, const std::string& source,
                                              const ProgressSink& progress) {
  const path::Path& path = streamed.plan.path;
  ErrorAmplificationScan scan(machine, amplification_spacing, source);
  planning::ServoStream stream(streamed.plan, machine, streamed.source.get());
  planning::ServoTick tick;
  int scanned = 0;
  long ticks = 0;
  while (stream.next(tick)) {
    // The segments before the tick's are final, and the stream forgets them only at its next tick.
    for (; scanned < tick.segment; ++scanned) {
      if (Status sampled = scan.add_segment(path, scanned); !sampled) return sampled.error();
    }
    if (progress && ++ticks % 65536 == 0) report_progress(progress, "checking the plan", -1.0, tick.line);
  }
  if (stream.error()) return *stream.error();
  for (; scanned < path.segment_end(); ++scanned) {
    if (Status sampled = scan.add_segment(path, scanned); !sampled) return sampled.error();
  }
  if (Status finished = scan.finish(path); !finished) return finished.error();
  return StreamedPlanCheck{scan.result(), streamed.plan.duration_s};
}

Result<InterpolateSummary> interpolate_streamed(const Machine& machine, planning::StreamedPlan& streamed,
                                                const StreamedPlanCheck& check,
                                                const InterpolateOptions& options,
                                                const std::vector<StepSink*>& sinks,
                                                const std::string& source) {
  if (Status valid = check_interpolate_options(options, !sinks.empty()); !valid) return valid.error();
  if (options.method == Method::estimating) {
    return make_error(ErrorCode::bad_input, "the estimating method needs the whole plan, not a stream");
  }
  InterpolateSummary summary = summary_before_run(machine, options, check.amplification);
  const std::optional<LawFitSettings> fit =
      options.method == Method::exact
          ? std::nullopt
          : std::optional<LawFitSettings>(LawFitSettings{.tolerance = 0.1 * summary.strut_tolerance});
  auto laws = StrutLaws::window(machine, streamed.plan.path, fit, source);
  if (!laws) return laws.error();
  IdealTiming timing = IdealTiming::window(streamed.plan.period_s);
  PlanWindowFeed feed(streamed, machine, timing, *laws);
  RunRecorder recorder(sinks, summary, options, check.duration_s);
  if (Status ran = run_carrier(machine, streamed.plan.path, timing, *laws, &feed, options,
                               actuator_step(machine, options), summary, recorder, source);
      !ran)
    return ran.error();
  if (Status finished = recorder.finish(); !finished) return finished.error();
  summary.peak_window_ticks = feed.peak_ticks();
  summary.peak_window_pieces = feed.peak_pieces();
  summary.peak_window_segments = feed.peak_segments();
  return summary;
}

Result<std::array<std::int64_t, kMaxActuators>> start_positions(const Machine& machine,
                                                                const path::Path& path, double step_mm) {
  auto ik = machine.mechanism->inverse(Pose{path.start.position_mm, path.start.rotation.toRotationMatrix()});
  if (!ik) return ik.error();
  const int n = machine.mechanism->actuator_count();
  const double step = machine.mechanism->actuators_are_angles() ? rad_from_deg(step_mm) : step_mm;
  std::array<double, kMaxActuators> values{};
  for (int j = 0; j < n; ++j) values[j] = (*ik)[j];
  return truncated_steps(values, n, step);
}

}  // namespace pkm::interpolation
