// The machine in the loop (servo/coupled_machine.hpp; goal ≥ 20× real time for the ch5 hexapod with six
// drives), for docs/PERFORMANCE.md. The ch5 hexapod as shipped (struts of 200 000 N/mm in series with
// 400 000 N/mm transmissions, the drives' loops every 0.25 ms) follows the planned helix's set points: one
// iteration is one 1 ms servo period (four loop periods of all six drives and the elastic machine between
// them), timed on its own into a fixed histogram (p50_us, p99_9_us, max_us beside the mean); the real-time
// factor is the motion's time over the computing time. Arg 0: the drives as shipped (ideal); 1: with
// Coulomb, static and viscous friction; 2: with every imperfection (friction, backlash, encoder counts, a
// one-period sampling delay).
#include <benchmark/benchmark.h>

#include <chrono>
#include <vector>

#include "bench_support.hpp"
#include "core/duration_histogram.hpp"
#include "servo/coupled_machine.hpp"
#include "servo/servo_plant.hpp"

namespace pkm {
namespace {

void BM_CoupledHelixPeriod(benchmark::State& state) {
  const Machine& machine = bench::ch5_hexapod();
  const bench::PlannedTicks& run = bench::ch5_helix_ticks();
  const int m = machine.mechanism->actuator_count();
  auto own = servo::machine_inertia(machine, machine.mechanism->home());
  if (!own) {
    state.SkipWithError(own.error().message.c_str());
    return;
  }
  const ActuatorVector inertia = own->diagonal().head(m) + servo::motor_inertia(machine.servo, m);
  auto design = servo::design_loops(machine, inertia);
  if (!design) {
    state.SkipWithError(design.error().message.c_str());
    return;
  }
  for (int j = 0; j < m && state.range(0) >= 1; ++j) {
    servo::ChannelGains& g = design->channels[j];
    g.friction_coulomb = 60.0, g.friction_static = 80.0, g.stribeck_speed = 1.0, g.friction_viscous = 0.2;
    if (state.range(0) == 2) g.backlash = 0.003, g.encoder_resolution = 0.0002;
  }
  if (state.range(0) == 2) design->sample_delay_periods = 1;
  const int steps = static_cast<int>(std::lround(run.period_s / machine.servo.loop_period_s));
  auto coupled = servo::CoupledMachine::make(machine, *design, run.period_s / steps);
  if (!coupled) {
    state.SkipWithError(coupled.error().message.c_str());
    return;
  }
  std::vector<servo::DriveVector> references(run.ticks.size(), servo::DriveVector::Zero());
  for (std::size_t k = 0; k < references.size(); ++k) references[k].head(m) = run.ticks[k].actuators;
  const auto restart = [&] { return coupled->reset(0.0, references[0], run.ticks[0].pose); };
  if (Status s = restart(); !s) {
    state.SkipWithError(s.error().message.c_str());
    return;
  }
  DurationHistogram time(100'000);
  using Clock = std::chrono::steady_clock;
  std::size_t k = 1;
  long periods = 0;
  for (auto _ : state) {
    const servo::DriveVector speed = (references[k] - references[k - 1]) / run.period_s;
    const Clock::time_point started = Clock::now();
    for (int i = 0; i < steps; ++i) {
      const Status stepped = coupled->step(
          references[k - 1] + (static_cast<double>(i) / steps) * (references[k] - references[k - 1]), speed);
      if (!stepped) {
        state.SkipWithError(stepped.error().message.c_str());
        return;
      }
    }
    time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    ++periods;
    if (++k == references.size()) {
      k = 1;
      state.PauseTiming();
      (void)restart();
      state.ResumeTiming();
    }
  }
  state.counters["realtime_factor"] =
      benchmark::Counter(static_cast<double>(periods) * run.period_s, benchmark::Counter::kIsRate);
  state.counters["loop_periods_per_servo_period"] = steps;
  bench::record_distribution(state, time);
}
BENCHMARK(BM_CoupledHelixPeriod)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
