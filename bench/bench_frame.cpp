// The frame finite-element model per path point (goal ≤ 1 ms for a frame of 200 elements, reusing
// the factorisation pattern), for docs/stiffness_frame.md and docs/PERFORMANCE.md: the ch5 hexapod on a frame
// of 200 beam elements (the six columns and the ring of examples/machines/hexapod_ch5_frame.yaml, each beam
// cut into elements: 6 columns × 17 + 6 ring beams × 16 + 2 more = 200) along the planned helix, every tick's
// pose made before the timing. One iteration is one FrameModel::compliance call (refill, L D Lᵀ
// factorisation, six solves), timed on its own into a fixed histogram (p50, p99, p99.9, worst beside the
// mean); BM_FrameDeflectionPerPoint times the deflection under a load (one solve, strut forces, nodal
// displacements).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "bench_support.hpp"
#include "stiffness/frame_model.hpp"

namespace pkm {
namespace {

const Machine& frame_machine() {
  static const Machine m = [] {
    auto loaded = load_machine_file(
        (std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines/hexapod_ch5_frame.yaml").string());
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded.value());
  }();
  return m;
}

// The example's frame with beam b cut into parts[b] equal elements (new nodes appended).
FrameParameters split_bench_frame(const FrameParameters& frame, const std::vector<int>& parts) {
  FrameParameters out = frame;
  out.beams.clear();
  for (std::size_t b = 0; b < frame.beams.size(); ++b) {
    const FrameBeam& beam = frame.beams[b];
    const Eigen::Vector3d from = frame.nodes[beam.from].position_mm, to = frame.nodes[beam.to].position_mm;
    int previous = beam.from;
    for (int k = 1; k <= parts[b]; ++k) {
      int next = beam.to;
      if (k < parts[b]) {
        next = static_cast<int>(out.nodes.size());
        out.nodes.push_back(
            {fmt::format("e{}", next), from + (to - from) * (double(k) / parts[b]), false, 0});
      }
      FrameBeam element = beam;
      element.from = previous;
      element.to = next;
      out.beams.push_back(element);
      previous = next;
    }
  }
  return out;
}

stiffness::FrameModel& bench_frame_model() {
  static stiffness::FrameModel model = [] {
    const Machine& machine = frame_machine();
    StiffnessParameters parameters = machine.stiffness;
    // 12 beams: the columns into 17 elements, the ring beams into 16, two of them into 17: 200 elements.
    std::vector<int> parts = {17, 17, 17, 17, 17, 17, 17, 17, 16, 16, 16, 16};
    parameters.frame = split_bench_frame(parameters.frame, parts);
    if (parameters.frame.beams.size() != 200)
      throw std::logic_error("the bench frame must have 200 elements");
    auto made = stiffness::FrameModel::make(*machine.mechanism, parameters);
    if (!made) throw std::runtime_error(made.error().message);
    return std::move(made.value());
  }();
  return model;
}

void BM_FrameCompliancePerPoint(benchmark::State& state) {
  const auto& poses = bench::ch5_helix_poses();
  stiffness::FrameModel& model = bench_frame_model();
  DurationHistogram time(1'000'000);
  bench::time_each_pose(state, poses, time, [&model](const Pose& pose) { return model.compliance(pose); });
  state.counters["mean_us"] = time.mean_us();
  state.counters["unknowns"] = model.unknowns();
  state.counters["factor_nonzeros"] = static_cast<double>(model.factor_nonzeros());
}
BENCHMARK(BM_FrameCompliancePerPoint)->Unit(benchmark::kMicrosecond);

void BM_FrameDeflectionPerPoint(benchmark::State& state) {
  const auto& poses = bench::ch5_helix_poses();
  stiffness::FrameModel& model = bench_frame_model();
  stiffness::FrameDeflection deflection = model.make_deflection();
  const statics::Wrench load{Eigen::Vector3d(300, -200, 500), Eigen::Vector3d(1e4, 0, -2e4)};
  DurationHistogram time(1'000'000);
  // The deflection lands in `deflection`, written by the library through the reference.
  bench::time_each_pose(state, poses, time,
                        [&](const Pose& pose) { return model.deflection(pose, load, deflection); });
  state.counters["mean_us"] = time.mean_us();
}
BENCHMARK(BM_FrameDeflectionPerPoint)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
