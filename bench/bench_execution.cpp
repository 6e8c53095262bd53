// The executor of planned motion (execution/step_executor.hpp), as LinuxCNC's servo thread runs it through
// pkmexec, for docs/PERFORMANCE.md: one iteration is one servo period — a nominal period taken in and one
// released — on a smooth six-drive motion, at 100 % feed (the planned steps released as they are) and at 70 %
// (τ between the plan's periods: the Catmull–Rom set point rounded to steps). Every period is also timed on
// its own into a fixed histogram (core/duration_histogram.hpp): counters p50_us, p99_9_us, max_us.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "core/duration_histogram.hpp"
#include "execution/step_executor.hpp"

namespace pkm {
namespace {

void run_periods(benchmark::State& state, double override_factor) {
  execution::ExecutorSettings settings;
  settings.min_position_steps.fill(-(std::int64_t{1} << 40));
  settings.max_position_steps.fill(std::int64_t{1} << 40);
  settings.rates = {12.0, 600.0};
  execution::StepExecutor executor(settings);
  executor.start({});
  execution::NominalPeriod nominal;
  execution::ExecutedPeriod out;
  long k = 0;
  auto next_nominal = [&] {
    ++k;
    for (int j = 0; j < kMaxActuators; ++j) {
      nominal.ideal_steps[j] = 50000.0 * (1.0 - std::cos(1e-3 * static_cast<double>(k) + j));
      nominal.position_steps[j] = std::llround(nominal.ideal_steps[j]);
    }
    nominal.line = static_cast<int>(k / 100);
  };
  while (executor.has_room()) {
    next_nominal();
    executor.push(nominal);
  }
  DurationHistogram histogram;
  const execution::ExecutionControls controls{override_factor, false, false};
  for (auto _ : state) {
    const auto started = std::chrono::steady_clock::now();
    if (executor.has_room()) {
      next_nominal();
      executor.push(nominal);
    }
    executor.period(controls, out);
    histogram.add(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - started)
            .count());
    benchmark::DoNotOptimize(out);
  }
  state.counters["p50_us"] = histogram.percentile_us(0.5);
  state.counters["p99_9_us"] = histogram.percentile_us(0.999);
  state.counters["max_us"] = histogram.max_us();
}

void BM_ExecutorPeriodFullFeed(benchmark::State& state) {
  run_periods(state, 1.0);
}
void BM_ExecutorPeriodScaled(benchmark::State& state) {
  run_periods(state, 0.7);
}

BENCHMARK(BM_ExecutorPeriodFullFeed);
BENCHMARK(BM_ExecutorPeriodScaled);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
