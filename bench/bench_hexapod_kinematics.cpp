// Hexapod IK and FK timings for docs/PERFORMANCE.md, on the dissertation's ch5 hexapod and on LinuxCNC's
// default genhexkins geometry (in mm), with the same pose sets as the genhexkins anchor figures
// (../shared/anchors.md):
//   IK per pose: random ±20 mm, ±10° around home (including the angle → matrix conversion, as genhexkins
//   does); FK warm: along a smooth path in 0.1 mm / 0.01° steps, each solve started from the previous pose;
//   FK cold: from home to random poses ±20 mm/±10° and ±50 mm/±20°.
// Counters: iterations per solve, fraction converged to the right pose (1e-6 mm), worst single call (µs).
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <vector>

#include "core/units.hpp"
#include "io/machine_file.hpp"
#include "machine/hexapod.hpp"

namespace pkm {
namespace {

const Hexapod& hexapod_of(const char* file) {
  static std::vector<std::unique_ptr<Machine>> keep;
  auto loaded =
      load_machine_file((std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines" / file).string());
  if (!loaded) throw std::runtime_error(loaded.error().message);
  keep.push_back(std::make_unique<Machine>(std::move(loaded.value())));
  return dynamic_cast<const Hexapod&>(*keep.back()->mechanism);
}

std::vector<PoseVector> random_poses(const Hexapod& h, double range_mm, double range_deg, int count,
                                     unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const PoseVector home = vector_from_pose(h.convention(), h.home());
  std::vector<PoseVector> out;
  for (int i = 0; i < count; ++i) {
    PoseVector c = home;
    for (int k = 0; k < 6; ++k) c[k] += u(rng) * (k < 3 ? range_mm : rad_from_deg(range_deg));
    out.push_back(c);
  }
  return out;
}

void BM_NoOp(benchmark::State& state) {
  for (auto _ : state) benchmark::ClobberMemory();
}
BENCHMARK(BM_NoOp);

void BM_IK(benchmark::State& state, const char* file) {
  const Hexapod& h = hexapod_of(file);
  const auto poses = random_poses(h, 20, 10, 4096, 1);
  std::size_t i = 0;
  double lengths[6];
  for (auto _ : state) {
    const PoseVector& c = poses[i++ & 4095];
    h.strut_lengths(pose_from_vector(h.convention(), c), lengths);
    benchmark::DoNotOptimize(lengths);
  }
}
BENCHMARK_CAPTURE(BM_IK, ch5, "hexapod_ch5.yaml");
BENCHMARK_CAPTURE(BM_IK, genhexkins, "hexapod_genhexkins.yaml");

struct FkStats {
  long solves = 0, converged = 0, iterations = 0;
  double worst_us = 0;
};

void report(benchmark::State& state, const FkStats& s) {
  state.counters["iterations"] = static_cast<double>(s.iterations) / static_cast<double>(s.solves);
  state.counters["converged"] = static_cast<double>(s.converged) / static_cast<double>(s.solves);
  state.counters["worst_us"] = s.worst_us;
}

void BM_FK_warm_path(benchmark::State& state, const char* file, bool keep_workspace) {
  const Hexapod& h = hexapod_of(file);
  // A circle of radius 40 mm with angles turning 0.01° per 0.1 mm step.
  const PoseVector home = vector_from_pose(h.convention(), h.home());
  std::vector<Pose> path;
  std::vector<ActuatorVector> lengths;
  for (int i = 0; i < 2513; ++i) {
    PoseVector c = home;
    const double s = i * 0.1 / 40.0;
    c[0] += 40 * std::sin(s);
    c[1] += 40 * (1 - std::cos(s));
    for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(0.01) * i * (k == 4 ? -0.5 : 1.0) * 0.1;
    path.push_back(pose_from_vector(h.convention(), c));
    lengths.push_back(*h.inverse(path.back()));
  }
  FkStats stats;
  std::size_t i = 1;
  Pose previous = path[0];
  PlatformFkWorkspace<6> workspace;
  const FkOptions options;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!keep_workspace) workspace.reset();
    auto fk = h.forward(lengths[i], previous, options, workspace);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    stats.worst_us = std::max(stats.worst_us, us);
    ++stats.solves;
    if (fk) {
      stats.iterations += fk->iterations;
      stats.converged += (fk->pose.position_mm - path[i].position_mm).norm() < 1e-6 ? 1 : 0;
    }
    previous = fk ? fk->pose : path[i];
    if (++i == path.size()) {
      i = 1;
      previous = path[0];
      workspace.reset();
    }
  }
  report(state, stats);
}
// "previous pose": each call starts from the previous solution only (as genhexkins does);
// "workspace": Hexapod::forward with a workspace, as a servo loop calls it: the previous call's factorisation
// and a start extrapolated from the last two solutions.
BENCHMARK_CAPTURE(BM_FK_warm_path, ch5_previous_pose, "hexapod_ch5.yaml", false);
BENCHMARK_CAPTURE(BM_FK_warm_path, ch5_workspace, "hexapod_ch5.yaml", true);
BENCHMARK_CAPTURE(BM_FK_warm_path, genhexkins_previous_pose, "hexapod_genhexkins.yaml", false);
BENCHMARK_CAPTURE(BM_FK_warm_path, genhexkins_workspace, "hexapod_genhexkins.yaml", true);

void BM_FK_cold(benchmark::State& state, const char* file, double range_mm, double range_deg) {
  const Hexapod& h = hexapod_of(file);
  const auto poses = random_poses(h, range_mm, range_deg, 4096, 2);
  std::vector<ActuatorVector> lengths;
  for (const auto& c : poses) lengths.push_back(*h.inverse(pose_from_vector(h.convention(), c)));
  FkStats stats;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    const auto t0 = std::chrono::steady_clock::now();
    auto fk = h.forward(lengths[k], h.home());
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    stats.worst_us = std::max(stats.worst_us, us);
    ++stats.solves;
    if (fk) {
      stats.iterations += fk->iterations;
      stats.converged += (fk->pose.position_mm - poses[k].head<3>()).norm() < 1e-6 ? 1 : 0;
    }
  }
  report(state, stats);
}
BENCHMARK_CAPTURE(BM_FK_cold, ch5_20mm_10deg, "hexapod_ch5.yaml", 20, 10);
BENCHMARK_CAPTURE(BM_FK_cold, ch5_50mm_20deg, "hexapod_ch5.yaml", 50, 20);
BENCHMARK_CAPTURE(BM_FK_cold, ch5_100mm_20deg, "hexapod_ch5.yaml", 100, 20);
BENCHMARK_CAPTURE(BM_FK_cold, ch5_200mm_30deg, "hexapod_ch5.yaml", 200, 30);
BENCHMARK_CAPTURE(BM_FK_cold, genhexkins_20mm_10deg, "hexapod_genhexkins.yaml", 20, 10);
BENCHMARK_CAPTURE(BM_FK_cold, genhexkins_50mm_20deg, "hexapod_genhexkins.yaml", 50, 20);
BENCHMARK_CAPTURE(BM_FK_cold, genhexkins_200mm_30deg, "hexapod_genhexkins.yaml", 200, 30);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
