#pragma once
// What the benchmarks share: the ch5 hexapod of the shipped examples, loaded once.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/duration_histogram.hpp"
#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "planning/servo_stream.hpp"
#include "program/part_program.hpp"

namespace pkm::bench {

/// examples/machines/hexapod_ch5.yaml of the source tree (PKM_SOURCE_DIR), loaded at the first call.
inline const Machine& ch5_hexapod() {
  static const Machine m = [] {
    auto loaded = load_machine_file(
        (std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines/hexapod_ch5.yaml").string());
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded.value());
  }();
  return m;
}

/// A shipped program planned on the ch5 hexapod at its servo rate, with every tick of the stream.
struct PlannedTicks {
  double period_s = 0.0;
  std::vector<planning::ServoTick> ticks;
};

/// examples/programs/NAME planned on the ch5 hexapod from where its programs start, at its servo rate.
inline planning::MotionPlan ch5_plan(const char* name) {
  const Machine& machine = ch5_hexapod();
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions interpret;
  interpret.start_mm = start.start_mm;
  interpret.start_abc_deg = start.start_abc_deg;
  auto program = program::load_part_program(
      (std::filesystem::path(PKM_SOURCE_DIR) / "examples/programs" / name).string(), interpret);
  if (!program) throw std::runtime_error(program.error().message);
  auto plan = planning::plan_motion(machine, *program, planning::PlanOptions{});
  if (!plan) throw std::runtime_error(plan.error().message);
  return std::move(*plan);
}

/// examples/programs/helix.ngc, planned once at the first call.
inline const PlannedTicks& ch5_helix_ticks() {
  static const PlannedTicks run = [] {
    const Machine& machine = ch5_hexapod();
    const planning::MotionPlan plan = ch5_plan("helix.ngc");
    PlannedTicks r;
    r.period_s = plan.period_s;
    planning::ServoStream stream(plan, machine);
    planning::ServoTick tick;
    while (stream.next(tick)) r.ticks.push_back(tick);
    return r;
  }();
  return run;
}

/// The poses of every tick of ch5_helix_ticks(), made once: the path points the per-point benchmarks
/// (stiffness, frame) run along.
inline const std::vector<Pose>& ch5_helix_poses() {
  static const std::vector<Pose> poses = [] {
    std::vector<Pose> out;
    for (const planning::ServoTick& tick : ch5_helix_ticks().ticks) out.push_back(tick.pose);
    return out;
  }();
  return poses;
}

/// The per-call times of a servo-rate function as counters beside the mean: calls, p50_us, p99_us,
/// p99_9_us, max_us.
inline void record_distribution(benchmark::State& state, const DurationHistogram& histogram) {
  const DurationDistribution d = histogram.distribution();
  state.counters["ticks"] = static_cast<double>(d.count);
  state.counters["p50_us"] = d.p50_us;
  state.counters["p99_us"] = d.p99_us;
  state.counters["p99_9_us"] = d.p99_9_us;
  state.counters["max_us"] = d.max_us;
}

/// Times the hot IK (`actuator_values`) of `poses` in turn, every call on its own: the yardstick the
/// per-tick benchmarks report their ratio to, in the same run.
inline void time_inverse_kinematics(benchmark::State& state, const Mechanism& mechanism,
                                    const std::vector<Pose>& poses) {
  DurationHistogram time(10'000);
  using Clock = std::chrono::steady_clock;
  std::size_t k = 0;
  double lengths[kMaxActuators];
  for (auto _ : state) {
    const Clock::time_point started = Clock::now();
    const bool ok = mechanism.actuator_values(poses[k], lengths);
    time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    if (!ok) {
      state.SkipWithError("inverse kinematics failed");
      break;
    }
    benchmark::DoNotOptimize(lengths);
    k = k + 1 == poses.size() ? 0 : k + 1;
  }
  record_distribution(state, time);
}

/// Times `call(pose)` on `poses` in turn, every call on its own, into `time` and its counters
/// (record_distribution); `call` returns a Result, whose error stops the benchmark.
template <class Call>
void time_each_pose(benchmark::State& state, const std::vector<Pose>& poses, DurationHistogram& time,
                    Call call) {
  using Clock = std::chrono::steady_clock;
  std::size_t k = 0;
  for (auto _ : state) {
    const Clock::time_point started = Clock::now();
    auto result = call(poses[k]);
    time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(result);
    k = k + 1 == poses.size() ? 0 : k + 1;
  }
  record_distribution(state, time);
}

}  // namespace pkm::bench
