// Rigid inverse dynamics per servo tick (goal ≤ 2 µs on the hexapod, so that a 1 kHz loop can
// compute feed-forward forces with margin), for docs/PERFORMANCE.md. The planned helix on the ch5 hexapod
// with the machine file's dynamics section: the motion of every tick (pose, twist and its rate by central
// differences, as `pkm plan --dynamics` takes them) is made before the timing; one iteration is one
// dynamics::inverse_dynamics call, timed on its own into a fixed histogram: counters p50_us, p99_us,
// p99_9_us, max_us beside the mean. BM_InverseKinematicsPerTick times the strut lengths of the same poses
// through the same interface, in the same run, for the ratio.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <vector>

#include "bench_support.hpp"
#include "core/duration_histogram.hpp"
#include "core/rotation.hpp"
#include "dynamics/rigid_dynamics.hpp"
#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "planning/servo_stream.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

const Machine& machine() {
  return bench::ch5_hexapod();
}

/// The helix's ticks as platform motions (central differences over the 1 ms period).
const std::vector<dynamics::PlatformMotion>& motions() {
  static const std::vector<dynamics::PlatformMotion> all = [] {
    const bench::PlannedTicks& run = bench::ch5_helix_ticks();
    std::vector<Pose> poses;
    for (const planning::ServoTick& tick : run.ticks) poses.push_back(tick.pose);
    std::vector<dynamics::PlatformMotion> out;
    const double h = run.period_s;
    for (std::size_t k = 1; k + 1 < poses.size(); ++k) {
      dynamics::PlatformMotion m;
      m.pose = poses[k];
      m.velocity_mm_s = (poses[k + 1].position_mm - poses[k - 1].position_mm) / (2 * h);
      m.acceleration_mm_s2 =
          (poses[k + 1].position_mm - 2 * poses[k].position_mm + poses[k - 1].position_mm) / (h * h);
      const Eigen::Vector3d in =
          rotation_vector_from_rotation(poses[k].rotation * poses[k - 1].rotation.transpose());
      const Eigen::Vector3d out_step =
          rotation_vector_from_rotation(poses[k + 1].rotation * poses[k].rotation.transpose());
      m.angular_velocity_rad_s = (in + out_step) / (2 * h);
      m.angular_acceleration_rad_s2 = (out_step - in) / (h * h);
      out.push_back(m);
    }
    return out;
  }();
  return all;
}

void BM_InverseDynamicsPerTick(benchmark::State& state) {
  const auto& all = motions();
  const Mechanism& mechanism = *machine().mechanism;
  const DynamicsParameters& parameters = machine().dynamics;
  DurationHistogram time(10'000);
  using Clock = std::chrono::steady_clock;
  std::size_t k = 0;
  for (auto _ : state) {
    const Clock::time_point started = Clock::now();
    auto forces = dynamics::inverse_dynamics(mechanism, parameters, all[k]);
    time.add(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started).count());
    if (!forces) {
      state.SkipWithError(forces.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(forces);
    k = k + 1 == all.size() ? 0 : k + 1;
  }
  bench::record_distribution(state, time);
}
BENCHMARK(BM_InverseDynamicsPerTick)->Unit(benchmark::kMicrosecond);

void BM_InverseKinematicsPerTick(benchmark::State& state) {
  static const std::vector<Pose> poses = [] {
    std::vector<Pose> out;
    for (const auto& m : motions()) out.push_back(m.pose);
    return out;
  }();
  bench::time_inverse_kinematics(state, *machine().mechanism, poses);
}
BENCHMARK(BM_InverseKinematicsPerTick)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
