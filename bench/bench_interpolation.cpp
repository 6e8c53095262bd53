// Interpolation down to drive steps (Smirnov 2019, chapter 5) on the dissertation's test hexapod and test
// line (−50, 0, 700) → (50, 0, 700), for docs/PERFORMANCE.md; goals: the corrected carrier method under 10 µs
// per period, its p99.9 too, beside the estimating-function method's time per tact, in one run.
//
// BM_PeriodTime: one iteration is one servo period of the real-time part, as `pkm interpolate` times it: the
// carrier step (ideal time, strut laws, chord check) and the quantisation (remainder registers, or the
// discreteness correction with its two FK solves and two Jacobians), on the planned ch5 line (acceleration,
// 50 mm/s, deceleration) at h = 1 ms and 0.1 ms, Δ = 1 µm; the run restarts at the line's end outside the
// timing. Every period is also timed on its own with the steady clock into a fixed histogram
// (core/duration_histogram.hpp; recording does not allocate): counters p50_us, p99_us, p99_9_us, max_us,
// periods (the count) and over_10us (periods above 10 µs), beside the mean (the benchmark's time).
//
// BM_EstimatingTact: the estimating-function interpolator (§5.2.1): time per tact with the dissertation's
// final candidate set (all six struts move, 64 candidates, one FK each), for docs/PERFORMANCE.md. One
// benchmark iteration is one tact; at the end of the line the run starts again (outside the timing).
// Counters: s_per_tact (shown with SI prefixes, e.g. 40u = 40 µs), fk_per_tact, s_per_fk (the dissertation's
// t_T) and mm_per_s, the contour speed this computation alone would allow: the dissertation's real-time bound
// V_K = progress per tact / time per tact (§5.2.1: 0.23 mm/s at t_T = 1 ms).
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>

#include "bench_support.hpp"
#include "core/duration_histogram.hpp"
#include "interpolation/methods/carrier_interpolator.hpp"
#include "interpolation/methods/estimating_function.hpp"
#include "interpolation/quantisation/discreteness_corrector.hpp"
#include "interpolation/quantisation/remainder_quantizer.hpp"
#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

const Machine& machine() {
  return bench::ch5_hexapod();
}

/// The 100 mm test line, starting exactly at (−50, 0, 700) (the example puts program Z0 at z = 700), planned
/// at `rate_hz`.
const planning::MotionPlan& ch5_line_plan(double rate_hz) {
  static std::map<double, planning::MotionPlan> plans;
  if (auto found = plans.find(rate_hz); found != plans.end()) return found->second;
  program::InterpretOptions options;
  options.start_mm = Eigen::Vector3d(-50.0, 0.0, 0.0);
  auto program = program::interpret_gcode("G21 G90 G17\nG1 X50 Y0 Z0 F3000\nM2\n", "ch5_line.ngc", options);
  if (!program) throw std::runtime_error(program.error().message);
  planning::PlanOptions plan_options;
  plan_options.rate_hz = rate_hz;
  auto planned = planning::plan_motion(machine(), *program, plan_options);
  if (!planned) throw std::runtime_error(planned.error().message);
  return plans.emplace(rate_hz, std::move(planned.value())).first->second;
}

const path::Path& ch5_line() {
  return ch5_line_plan(1000.0).path;
}

enum class PeriodMethod { exact, carrier, carrier_corrected };

// The real-time part of one carrier period, repeated along the line, each period timed on its own.
void BM_PeriodTime(benchmark::State& state, PeriodMethod method, double period_s) {
  const planning::MotionPlan& plan = ch5_line_plan(1.0 / period_s);
  const path::Path& path = plan.path;
  const auto laws = method == PeriodMethod::exact
                        ? interpolation::StrutLaws::exact(machine(), path, "ch5_line.ngc")
                        : interpolation::StrutLaws::fit(machine(), path, {}, "ch5_line.ngc");
  auto timing = interpolation::IdealTiming::from_plan(plan, machine());
  if (!laws || !timing) {
    state.SkipWithError("strut laws or timing failed");
    return;
  }
  interpolation::CarrierSettings settings;
  settings.period_s = period_s;
  const interpolation::ContourGauge gauge(machine(), path);
  interpolation::CorrectorSettings corrector_settings;
  corrector_settings.step = 0.001;
  std::optional<interpolation::CarrierInterpolator> carrier;
  std::optional<interpolation::DiscretenessCorrector> corrector;
  interpolation::RemainderQuantizer remainder(6, 0.001);
  const auto restart = [&]() -> bool {
    carrier.emplace(*laws, *timing, settings);
    std::array<double, kMaxActuators> start{};
    if (!carrier->start(start)) return false;
    corrector.emplace(machine(), path, gauge, corrector_settings);
    remainder.start(start);
    return static_cast<bool>(corrector->start(start));
  };
  if (!restart()) {
    state.SkipWithError("start failed");
    return;
  }
  interpolation::CarrierPeriod period;
  interpolation::StepPeriod out;
  DurationHistogram period_time(10'000);
  using Clock = std::chrono::steady_clock;
  for (auto _ : state) {
    const Clock::time_point started = Clock::now();
    if (!carrier->next(period)) {
      state.PauseTiming();
      if (!restart()) {
        state.SkipWithError("restart failed");
        break;
      }
      state.ResumeTiming();
      continue;
    }
    if (method == PeriodMethod::carrier_corrected) {
      if (!corrector->quantize(period, out)) {
        state.SkipWithError("correction failed");
        break;
      }
    } else {
      remainder.quantize(period, out);
    }
    period_time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    benchmark::DoNotOptimize(out);
  }
  const DurationDistribution d = period_time.distribution();
  state.counters["periods"] = static_cast<double>(d.count);
  state.counters["p50_us"] = d.p50_us;
  state.counters["p99_us"] = d.p99_us;
  state.counters["p99_9_us"] = d.p99_9_us;
  state.counters["max_us"] = d.max_us;
  state.counters["over_10us"] = static_cast<double>(d.over_budget);
}
BENCHMARK_CAPTURE(BM_PeriodTime, corrected_1kHz, PeriodMethod::carrier_corrected, 1e-3)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PeriodTime, corrected_10kHz, PeriodMethod::carrier_corrected, 1e-4)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PeriodTime, carrier_1kHz, PeriodMethod::carrier, 1e-3)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PeriodTime, carrier_10kHz, PeriodMethod::carrier, 1e-4)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PeriodTime, exact_1kHz, PeriodMethod::exact, 1e-3)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PeriodTime, exact_10kHz, PeriodMethod::exact, 1e-4)->Unit(benchmark::kMicrosecond);

// What the machine takes from a running thread, whatever it runs: a loop that only reads the steady clock,
// the gaps between consecutive readings (interrupts, preemption, a hypervisor). A gap inside a timed period
// adds to it, so a period of t µs is hit with a probability of about gaps_over_10us_per_s · t: the share of
// periods above 10 µs that no change of the code removes, only a shorter period.
void BM_ClockGaps(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  DurationHistogram gaps(10'000);
  Clock::time_point previous = Clock::now();
  const Clock::time_point started = previous;
  for (auto _ : state) {
    const Clock::time_point now = Clock::now();
    gaps.add(std::chrono::duration_cast<std::chrono::nanoseconds>(now - previous).count());
    previous = now;
  }
  const double seconds = std::chrono::duration<double>(previous - started).count();
  state.counters["gaps_over_10us_per_s"] =
      seconds > 0.0 ? static_cast<double>(gaps.over_budget()) / seconds : 0.0;
  state.counters["max_gap_us"] = gaps.max_us();
  state.counters["p99_9_gap_us"] = gaps.percentile_us(0.999);
}
BENCHMARK(BM_ClockGaps)->MinTime(1.0);

void BM_EstimatingTact(benchmark::State& state, interpolation::CandidateSet set, double step_mm) {
  interpolation::EstimatingSettings settings;
  settings.step_mm = step_mm;
  settings.deviation_mm = step_mm;
  settings.candidates = set;
  interpolation::EstimatingInterpolator interpolator(machine(), ch5_line(), settings, "ch5_line.ngc");
  if (Status started = interpolator.start(); !started) {
    state.SkipWithError(started.error().message.c_str());
    return;
  }
  long tacts = 0;
  long fk_solves = 0;
  double progress_mm = 0.0;
  interpolation::Tact tact;
  for (auto _ : state) {
    if (!interpolator.next(tact)) {
      state.PauseTiming();
      if (interpolator.error()) {
        state.SkipWithError(interpolator.error()->message.c_str());
        break;
      }
      fk_solves += interpolator.statistics().fk_solves;
      if (Status restarted = interpolator.start(); !restarted) {
        state.SkipWithError(restarted.error().message.c_str());
        break;
      }
      state.ResumeTiming();
      continue;  // the restart's iteration counts as a tact of no progress; one in thousands
    }
    ++tacts;
    progress_mm += tact.progress_mm;
    benchmark::DoNotOptimize(tact);
  }
  fk_solves += interpolator.statistics().fk_solves;
  using benchmark::Counter;
  state.counters["s_per_tact"] = Counter(static_cast<double>(tacts), Counter::kIsRate | Counter::kInvert);
  state.counters["fk_per_tact"] = tacts > 0 ? static_cast<double>(fk_solves) / tacts : 0.0;
  state.counters["s_per_fk"] = Counter(static_cast<double>(fk_solves), Counter::kIsRate | Counter::kInvert);
  state.counters["mm_per_tact"] = tacts > 0 ? progress_mm / tacts : 0.0;
  state.counters["mm_per_s"] = Counter(progress_mm, Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_EstimatingTact, all_six_step_0_001mm, interpolation::CandidateSet::all_six, 0.001)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_EstimatingTact, all_six_step_0_01mm, interpolation::CandidateSet::all_six, 0.01)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
