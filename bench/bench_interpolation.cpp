// Interpolation down to drive steps (spec ch5) on the seeds' test hexapod and test line (−50, 0, 700) →
// (50, 0, 700), for docs/PERFORMANCE.md; goal (issue 5): the corrected carrier method under 10 µs per period,
// beside the estimating-function method's time per tact, in one run.
//
// BM_CarrierPeriod: one iteration is one servo period of the real-time part: the carrier step (ideal time,
// strut laws, chord check) and the quantisation (remainder registers, or the discreteness correction with its
// two FK solves and two Jacobians). At 50 mm/s, h = 1 ms, Δ = 1 µm; the run restarts at the line's end
// outside the timing. Counter s_per_period.
//
// BM_EstimatingTact: the estimating-function interpolator (§4): time per tact with the seed's final candidate
// set (all six struts move, 64 candidates, one FK each), for docs/PERFORMANCE.md. One benchmark iteration is
// one tact; at the end of the line the run starts again (outside the timing). Counters: s_per_tact (shown
// with SI prefixes, e.g. 40u = 40 µs), fk_per_tact, s_per_fk (the seed's t_T) and mm_per_s, the contour speed
// this computation alone would allow: the seed's real-time bound V_K = progress per tact / time per tact
// (§4.5, case E7: 0.23 mm/s at t_T = 1 ms).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>

#include "interpolation/carrier_interpolator.hpp"
#include "interpolation/discreteness_corrector.hpp"
#include "interpolation/estimating_function.hpp"
#include "interpolation/remainder_quantizer.hpp"
#include "machine/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

const Machine& machine() {
  static const Machine m = [] {
    auto loaded = load_machine_file(
        (std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines/hexapod_ch5.yaml").string());
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded.value());
  }();
  return m;
}

/// The 100 mm test line, starting exactly at (−50, 0, 700) (the example puts program Z0 at z = 700).
const path::Path& ch5_line() {
  static const planning::MotionPlan plan = [] {
    program::InterpretOptions options;
    options.start_mm = Eigen::Vector3d(-50.0, 0.0, 0.0);
    auto program = program::interpret_gcode("G21 G90 G17\nG1 X50 Y0 Z0 F3000\nM2\n", "ch5_line.ngc", options);
    if (!program) throw std::runtime_error(program.error().message);
    auto planned = planning::plan_motion(machine(), *program, {});
    if (!planned) throw std::runtime_error(planned.error().message);
    return std::move(planned.value());
  }();
  return plan.path;
}

// The real-time part of one carrier period, repeated along the line.
void BM_CarrierPeriod(benchmark::State& state, bool corrected) {
  const path::Path& path = ch5_line();
  const auto laws = interpolation::StrutLaws::fit(machine(), path, {}, "ch5_line.ngc");
  if (!laws) {
    state.SkipWithError(laws.error().message.c_str());
    return;
  }
  const interpolation::IdealTiming timing = interpolation::IdealTiming::constant_speed(path.length(), 50.0);
  interpolation::CarrierSettings settings;
  settings.period_s = 0.001;
  const interpolation::ContourGauge gauge(machine(), path);
  interpolation::CorrectorSettings corrector_settings;
  corrector_settings.step = 0.001;
  std::optional<interpolation::CarrierInterpolator> carrier;
  std::optional<interpolation::DiscretenessCorrector> corrector;
  interpolation::RemainderQuantizer remainder(6, 0.001);
  const auto restart = [&]() -> bool {
    carrier.emplace(*laws, timing, settings);
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
  long periods = 0;
  for (auto _ : state) {
    if (!carrier->next(period)) {
      state.PauseTiming();
      if (!restart()) {
        state.SkipWithError("restart failed");
        break;
      }
      state.ResumeTiming();
      continue;
    }
    if (corrected) {
      if (!corrector->quantize(period, out)) {
        state.SkipWithError("correction failed");
        break;
      }
    } else {
      remainder.quantize(period, out);
    }
    ++periods;
    benchmark::DoNotOptimize(out);
  }
  using benchmark::Counter;
  state.counters["s_per_period"] = Counter(static_cast<double>(periods), Counter::kIsRate | Counter::kInvert);
}
BENCHMARK_CAPTURE(BM_CarrierPeriod, corrected, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CarrierPeriod, naive_registers, false)->Unit(benchmark::kMicrosecond);

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
