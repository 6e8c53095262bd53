// The elastic machine along a planned run (goal ≥ 100× real time, so that `pkm plan --dynamics
// --elastic` costs little beside the planning), for docs/PERFORMANCE.md. The planned helix on the ch5 hexapod
// with the machine file's dynamics section (200 N/µm struts, quadratic friction), its servo ticks at 1 kHz
// made before the timing; one iteration is the whole run through dynamics::RunElastic (the integration with
// the response at every tick, as `pkm plan` does it, without the file). Counters: realtime_factor (simulated
// seconds per wall second), steps and right-hand sides per simulated second, ns per right-hand side.
// BM_ElasticRightHandSide times one right-hand side at the ticks' poses, BM_NoOp the loop itself.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <vector>

#include "bench_support.hpp"
#include "dynamics/run_elastic.hpp"
#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "planning/servo_stream.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

const Machine& elastic_machine() {
  return bench::ch5_hexapod();
}

using PlannedRun = bench::PlannedTicks;

const PlannedRun& helix_run() {
  return bench::ch5_helix_ticks();
}

void BM_ElasticHelixRun(benchmark::State& state) {
  const PlannedRun& run = helix_run();
  const double simulated_s = run.ticks.back().time_s - run.ticks.front().time_s;
  double wall_s = 0.0;
  dynamics::IntegrationCounters counters;
  for (auto _ : state) {
    const auto started = std::chrono::steady_clock::now();
    auto elastic = dynamics::RunElastic::make(elastic_machine(), run.period_s, {});
    if (!elastic) {
      state.SkipWithError(elastic.error().message.c_str());
      break;
    }
    for (const planning::ServoTick& t : run.ticks) {
      if (Status added = elastic->add(t.time_s, t.line, t.pose, t.actuators); !added) {
        state.SkipWithError(added.error().message.c_str());
        break;
      }
    }
    if (Status finished = elastic->finish(); !finished) state.SkipWithError(finished.error().message.c_str());
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    counters = elastic->summary().counters;
    benchmark::DoNotOptimize(elastic->summary().max_tool_error_mm);
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["simulated_s"] = simulated_s;
  state.counters["realtime_factor"] = simulated_s * iterations / wall_s;
  state.counters["steps_per_simulated_s"] = counters.accepted_steps / simulated_s;
  state.counters["rhs_per_simulated_s"] = counters.evaluations / simulated_s;
  state.counters["ns_per_rhs"] = wall_s / iterations / counters.evaluations * 1e9;
}
BENCHMARK(BM_ElasticHelixRun)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ElasticRightHandSide(benchmark::State& state) {
  const PlannedRun& run = helix_run();
  auto model = dynamics::make_elastic_model(elastic_machine());
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  dynamics::ElasticWorkspace workspace;
  dynamics::CoordinateVector rates(6), accelerations;
  rates << 20.0, -10.0, 5.0, 0.01, -0.02, 0.005;
  dynamics::DriveSetpoint drives;
  std::size_t k = 0;
  for (auto _ : state) {
    const planning::ServoTick& t = run.ticks[k];
    drives.position_mm = t.actuators;
    drives.rate_mm_s = ActuatorVector::Zero(t.actuators.size());
    if (Status s = dynamics::elastic_accelerations(*model, t.pose, rates, drives, workspace, accelerations);
        !s) {
      state.SkipWithError(s.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(accelerations);
    k = k + 1 == run.ticks.size() ? 0 : k + 1;
  }
}
BENCHMARK(BM_ElasticRightHandSide)->Unit(benchmark::kNanosecond);

void BM_NoOp(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(state.iterations());
}
BENCHMARK(BM_NoOp)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
