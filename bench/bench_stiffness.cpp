// The strut-only tool compliance per path point (goal ≤ 1 µs on the hexapod), for
// docs/PERFORMANCE.md: the ch5 hexapod with its struts' stiffness along the planned helix, every tick's pose
// made before the timing; one iteration is one stiffness::strut_compliance call, timed on its own into a
// fixed histogram (p50, p99, p99.9, worst beside the mean). BM_StrutLinesInverseKinematics times the strut
// lengths of the same poses through the same interface, in the same run, for the ratio.
#include <benchmark/benchmark.h>

#include <vector>

#include "bench_support.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm {
namespace {

void BM_StrutCompliancePerPoint(benchmark::State& state) {
  const auto& poses = bench::ch5_helix_poses();
  const Machine& machine = bench::ch5_hexapod();
  auto parameters = stiffness::strut_stiffness_of(machine);
  if (!parameters) {
    state.SkipWithError(parameters.error().message.c_str());
    return;
  }
  DurationHistogram time(10'000);
  bench::time_each_pose(state, poses, time, [&](const Pose& pose) {
    return stiffness::strut_compliance(*machine.mechanism, *parameters, pose);
  });
}
BENCHMARK(BM_StrutCompliancePerPoint)->Unit(benchmark::kMicrosecond);

void BM_StrutLinesInverseKinematics(benchmark::State& state) {
  bench::time_inverse_kinematics(state, *bench::ch5_hexapod().mechanism, bench::ch5_helix_poses());
}
BENCHMARK(BM_StrutLinesInverseKinematics)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
