// The servo simulation (goal ≥ 10⁶ simulated servo periods per second for six drives, i.e. a 60 s
// program at 1 kHz in < 0.1 s), for docs/PERFORMANCE.md. The ch5 hexapod's six drives, tuned to the technical
// optimum from its servo: section, on the coupled inertia of the machine at home with the motors, follow the
// planned helix's set points (one loop step per 1 ms period, the set point's speed fed forward as the
// simulator's input). One iteration is one period of all six drives, timed on its own into a fixed histogram
// (p50_us, p99_9_us, max_us beside the mean), with the ideal drives and with every imperfection (friction,
// backlash, encoder counts, a sample delay). BM_ServoRunPerTick is the whole `pkm servo` simulation per
// tick: the same plus the contour error by forward kinematics at the tick and at mid-period.
#include <benchmark/benchmark.h>

#include <chrono>
#include <vector>

#include "bench_support.hpp"
#include "core/duration_histogram.hpp"
#include "servo/loop_design.hpp"
#include "servo/servo_plant.hpp"
#include "servo/servo_run.hpp"
#include "servo/servo_simulator.hpp"

namespace pkm {
namespace {

// The helix as the servo's input: set points, commanded poses and lines.
const servo::ServoRunInput& helix_input() {
  static const servo::ServoRunInput input = [] {
    const bench::PlannedTicks& run = bench::ch5_helix_ticks();
    servo::ServoRunInput in;
    in.period_s = run.period_s;
    for (const planning::ServoTick& tick : run.ticks) {
      in.time_s.push_back(tick.time_s);
      in.line.push_back(tick.line);
      in.setpoint.push_back(tick.actuators);
      in.pose.push_back(tick.pose);
    }
    return in;
  }();
  return input;
}

void BM_ServoPeriodSixDrives(benchmark::State& state) {
  const Machine& machine = bench::ch5_hexapod();
  const servo::ServoRunInput& input = helix_input();
  const int m = machine.mechanism->actuator_count();
  auto own = servo::machine_inertia(machine, machine.mechanism->home());
  if (!own) {
    state.SkipWithError(own.error().message.c_str());
    return;
  }
  servo::DriveMatrix inertia = *own;
  inertia.diagonal().head(m) += servo::motor_inertia(machine.servo, m);
  auto design = servo::design_loops(machine, inertia.diagonal().head(m));
  if (!design) {
    state.SkipWithError(design.error().message.c_str());
    return;
  }
  if (state.range(0) == 1) {
    // Every imperfection on (docs/servo.md): friction with its eight sub-steps per half period, backlash, the
    // encoder's counts and a one-period delay.
    for (int j = 0; j < m; ++j) {
      servo::ChannelGains& g = design->channels[j];
      g.friction_coulomb = 60.0, g.friction_static = 80.0, g.stribeck_speed = 1.0, g.friction_viscous = 0.2;
      g.backlash = 0.003, g.encoder_resolution = 0.0002;
    }
    design->sample_delay_periods = 1;
  }
  servo::ServoSimulator simulator(*design, input.period_s);
  servo::DriveMatrix inverse = servo::DriveMatrix::Zero();
  inverse.topLeftCorner(m, m) = inertia.topLeftCorner(m, m).inverse();
  simulator.set_inverse_inertia(inverse);
  std::vector<servo::DriveVector> references(input.setpoint.size(), servo::DriveVector::Zero());
  for (std::size_t k = 0; k < references.size(); ++k) references[k].head(m) = input.setpoint[k];
  simulator.reset(references[0]);
  DurationHistogram time(10'000);
  using Clock = std::chrono::steady_clock;
  std::size_t k = 1;
  servo::DriveVector speed;
  for (auto _ : state) {
    speed = (references[k] - references[k - 1]) / input.period_s;
    const Clock::time_point started = Clock::now();
    simulator.step(references[k], speed);
    time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    benchmark::DoNotOptimize(simulator.position());
    if (++k == references.size()) {
      k = 1;
      simulator.reset(references[0]);
    }
  }
  state.counters["periods_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  bench::record_distribution(state, time);
}
// Arg 0: the ideal drives; 1: with every imperfection.
BENCHMARK(BM_ServoPeriodSixDrives)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);

void BM_ServoRunPerTick(benchmark::State& state) {
  const Machine& machine = bench::ch5_hexapod();
  const servo::ServoRunInput& input = helix_input();
  auto plant = servo::plant_along_run(machine, input, 10);
  if (!plant) {
    state.SkipWithError(plant.error().message.c_str());
    return;
  }
  const int m = machine.mechanism->actuator_count();
  auto design = servo::design_loops(machine, plant->inertia.front().diagonal().head(m));
  if (!design) {
    state.SkipWithError(design.error().message.c_str());
    return;
  }
  long ticks = 0;
  for (auto _ : state) {
    auto summary = servo::run_servo(machine, *design, *plant, input, 1, {});
    if (!summary) {
      state.SkipWithError(summary.error().message.c_str());
      break;
    }
    ticks += summary->ticks;
    benchmark::DoNotOptimize(summary);
  }
  state.counters["ticks_per_s"] = benchmark::Counter(static_cast<double>(ticks), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ServoRunPerTick)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
