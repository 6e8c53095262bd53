// Time per all-assembly-modes solve of a hexapod (Mechanism::assembly_modes, polished and
// labelled), on random general 6-6 geometries (goal ≤ 1.25 ms, 10× fkSGP's 12.5 ms), on random 3-fold
// symmetric machine layouts, on Dietmaier's 40-real instance, and on the shipped machines (6-3 and 3-6: the
// 1-D scan), and on the shipped carriage machines (hexaglide, rotopod: their carriage joints' Gough–Stewart
// platform; triglide: three spheres). Each benchmark cycles through a fixed set of instances made once; the
// worst single solve is reported beside the mean (docs/PERFORMANCE.md). The *_every_core variants let one
// solve follow its paths on every core (FkOptions::threads = 0; wall-clock time); BM_StewartAllModesKernels
// compares the tracker's baseline and AVX2/FMA kernels.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>

#include "core/wide_kernels.hpp"
#include "io/machine_file.hpp"
#include "kinematics/stewart_all_modes.hpp"
#include "machine/hexapod.hpp"

namespace pkm {
namespace {

using Joints = std::array<Eigen::Vector3d, 6>;

struct Instance {
  std::shared_ptr<const void> owner;  ///< keeps the mechanism alive
  const Mechanism* mechanism;
  ActuatorVector q;
};

Pose bench_random_pose(std::mt19937_64& rng, double tilt_rad, double height_mm) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Pose pose;
  const Eigen::Vector3d axis(u(rng), u(rng), u(rng));
  pose.rotation = Eigen::AngleAxisd(tilt_rad * u(rng), axis.normalized()).toRotationMatrix();
  pose.position_mm = Eigen::Vector3d(100 * u(rng), 100 * u(rng), height_mm + 100 * u(rng));
  return pose;
}

Instance hexapod_instance(const Joints& base, const Joints& platform, const Pose& pose) {
  HexapodGeometry geometry{base, platform};
  auto hexapod = std::make_shared<Hexapod>(geometry, AngleConvention::abc, pose);
  Instance instance{hexapod, hexapod.get(), ActuatorVector(6)};
  for (int j = 0; j < 6; ++j) instance.q[j] = (pose.to_base(platform[j]) - base[j]).norm();
  return instance;
}

// Random general 6-6 geometries at random poses.
struct JointSet {
  Joints base, platform;
  Pose pose;
};
std::vector<JointSet> general_joint_sets() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<JointSet> out;
  for (int i = 0; i < 50; ++i) {
    JointSet set;
    for (int j = 0; j < 6; ++j) {
      set.base[j] = Eigen::Vector3d(500 * u(rng), 500 * u(rng), 100 * u(rng));
      set.platform[j] = Eigen::Vector3d(250 * u(rng), 250 * u(rng), 60 * u(rng));
    }
    set.pose = bench_random_pose(rng, 1.0, 500.0);
    out.push_back(set);
  }
  return out;
}

std::vector<Instance> general_instances() {
  std::vector<Instance> out;
  for (const JointSet& set : general_joint_sets())
    out.push_back(hexapod_instance(set.base, set.platform, set.pose));
  return out;
}

std::vector<Instance> symmetric_instances() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Instance> out;
  for (int i = 0; i < 50; ++i) {
    const double rb = 200 + 400 * u(rng), gb = 1 + 12 * u(rng), rp = 60 + 140 * u(rng), gp = 1 + 12 * u(rng);
    Joints base, ring;
    for (int k = 0; k < 3; ++k) {
      for (int side = 0; side < 2; ++side) {
        const double sign = side ? 1.0 : -1.0;
        const double a = (120.0 * k + sign * gb) * M_PI / 180.0,
                     b = (60.0 + 120.0 * k + sign * gp) * M_PI / 180.0;
        base[2 * k + side] = Eigen::Vector3d(rb * std::cos(a), rb * std::sin(a), 0.0);
        ring[2 * k + side] = Eigen::Vector3d(rp * std::cos(b), rp * std::sin(b), 0.0);
      }
    }
    Joints platform;
    for (int j = 0; j < 6; ++j) platform[j] = ring[(j + 5) % 6];
    out.push_back(hexapod_instance(base, platform, bench_random_pose(rng, 0.5, 450.0)));
  }
  return out;
}

std::vector<Instance> dietmaier_instance() {
  const double unit_mm = 100.0;
  const Joints base = {Eigen::Vector3d(0, 0, 0),         {1.107915, 0, 0},
                       {0.549094, 0.756063, 0},          {0.735077, -0.223935, 0.525991},
                       {0.514188, -0.526063, -0.368418}, {0.590473, 0.094733, -0.205018}};
  const Joints platform = {Eigen::Vector3d(0, 0, 0),       {0.542805, 0, 0},
                           {0.956919, -0.528915, 0},       {0.665885, -0.353482, 1.402538},
                           {0.478359, 1.158742, 0.107672}, {-0.137087, -0.235121, 0.353913}};
  const std::array<double, 6> lengths = {1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071};
  Joints b, p;
  for (int j = 0; j < 6; ++j) {
    b[j] = base[j] * unit_mm;
    p[j] = platform[j] * unit_mm;
  }
  std::vector<Instance> out;
  Instance instance = hexapod_instance(b, p, Pose{});
  for (int j = 0; j < 6; ++j) instance.q[j] = lengths[j] * unit_mm;
  out.push_back(std::move(instance));
  return out;
}

std::vector<Instance> shipped_instances(const char* file) {
  auto loaded =
      load_machine_file((std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines" / file).string());
  if (!loaded) throw std::runtime_error(loaded.error().message);
  auto machine = std::make_shared<Machine>(std::move(loaded.value()));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Instance> out;
  const Pose home = machine->mechanism->home();
  for (int i = 0; i < 20; ++i) {
    Pose pose = home;
    pose.position_mm += Eigen::Vector3d(50 * u(rng), 50 * u(rng), 30 * u(rng));
    pose.rotation =
        Eigen::AngleAxisd(0.2 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()) * pose.rotation;
    auto q = machine->mechanism->inverse(pose);
    if (!q) continue;
    out.push_back(Instance{machine, machine->mechanism.get(), *q});
  }
  return out;
}

// `threads`: FkOptions::threads (1: the caller's thread; 0: every core, timed in wall-clock time).
void BM_AssemblyModes(benchmark::State& state, std::vector<Instance> (*make)(), int threads) {
  const std::vector<Instance> instances = make();
  FkOptions options;
  options.threads = threads;
  std::size_t next = 0;
  double worst_s = 0.0, modes = 0.0, solves = 0.0;
  for (auto _ : state) {
    const Instance& instance = instances[next++ % instances.size()];
    const auto start = std::chrono::steady_clock::now();
    auto result = instance.mechanism->assembly_modes(instance.q, options);
    worst_s =
        std::max(worst_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!result) state.SkipWithError(result.error().message.c_str());
    benchmark::DoNotOptimize(result);
    if (result) modes += static_cast<double>(result->solutions.size());
    solves += 1.0;
  }
  state.counters["worst_ms"] = worst_s * 1e3;
  state.counters["real_modes"] = solves > 0 ? modes / solves : 0.0;
}

// The homotopy alone (stewart_all_modes: no polishing, no labels) on the general geometries, with the
// tracker's kernels built for the baseline processor or for AVX2/FMA: what the run-time choice gains.
void BM_StewartAllModesKernels(benchmark::State& state, bool wide) {
  std::vector<std::array<double, 6>> lengths;
  const std::vector<JointSet> sets = general_joint_sets();
  for (const JointSet& set : sets) {
    std::array<double, 6> l;
    for (int j = 0; j < 6; ++j) l[j] = (set.pose.to_base(set.platform[j]) - set.base[j]).norm();
    lengths.push_back(l);
  }
  StewartAllModesOptions options;
  options.tracking.wide_kernels = wide;
  std::size_t next = 0;
  double steps = 0.0, solves = 0.0;
  for (auto _ : state) {
    const std::size_t k = next++ % sets.size();
    const StewartAllModes all = stewart_all_modes(sets[k].base, sets[k].platform, lengths[k], options);
    benchmark::DoNotOptimize(all);
    steps += all.steps;
    solves += 1.0;
  }
  state.counters["steps"] = solves > 0 ? steps / solves : 0.0;
  state.counters["wide_kernels"] = wide && wide_kernels_available() ? 1.0 : 0.0;
}

std::vector<Instance> ch5_instances() {
  return shipped_instances("hexapod_ch5.yaml");
}
std::vector<Instance> genhexkins_instances() {
  return shipped_instances("hexapod_genhexkins.yaml");
}
std::vector<Instance> delta30_instances() {
  return shipped_instances("hexapod_ch3_delta30.yaml");
}
// The carriage machines: the Gough–Stewart platform of their carriage joints
// (machine/carriage_assembly_modes).
std::vector<Instance> hexaglide_instances() {
  return shipped_instances("hexaglide.yaml");
}
std::vector<Instance> rotopod_instances() {
  return shipped_instances("rotopod.yaml");
}
std::vector<Instance> triglide_instances() {
  return shipped_instances("triglide.yaml");
}

BENCHMARK_CAPTURE(BM_AssemblyModes, general_6_6, general_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, general_6_6_every_core, general_instances, 0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_AssemblyModes, symmetric_6_6, symmetric_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, symmetric_6_6_every_core, symmetric_instances, 0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_AssemblyModes, dietmaier_40_real, dietmaier_instance, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_ch3_delta30_6_6, delta30_instances, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_ch5_6_3_scan, ch5_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_genhexkins_3_6_scan, genhexkins_instances, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_hexaglide, hexaglide_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_rotopod, rotopod_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_triglide, triglide_instances, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StewartAllModesKernels, general_baseline, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StewartAllModesKernels, general_avx2_fma, true)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
