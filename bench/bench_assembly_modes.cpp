// Issue 20: time per all-assembly-modes solve of a hexapod (Mechanism::assembly_modes, polished and
// labelled), on random general 6-6 geometries (goal ≤ 1.25 ms, 10× fkSGP's 12.5 ms), on random 3-fold
// symmetric machine layouts, on Dietmaier's 40-real instance, and on the shipped machines (6-3 and 3-6: the
// 1-D scan). Each benchmark cycles through a fixed set of instances made once; the worst single solve is
// reported beside the mean (docs/PERFORMANCE.md).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>

#include "io/machine_file.hpp"
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

std::vector<Instance> general_instances() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Instance> out;
  for (int i = 0; i < 50; ++i) {
    Joints base, platform;
    for (int j = 0; j < 6; ++j) {
      base[j] = Eigen::Vector3d(500 * u(rng), 500 * u(rng), 100 * u(rng));
      platform[j] = Eigen::Vector3d(250 * u(rng), 250 * u(rng), 60 * u(rng));
    }
    out.push_back(hexapod_instance(base, platform, bench_random_pose(rng, 1.0, 500.0)));
  }
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

void BM_AssemblyModes(benchmark::State& state, std::vector<Instance> (*make)()) {
  const std::vector<Instance> instances = make();
  std::size_t next = 0;
  double worst_s = 0.0, modes = 0.0, solves = 0.0;
  for (auto _ : state) {
    const Instance& instance = instances[next++ % instances.size()];
    const auto start = std::chrono::steady_clock::now();
    auto result = instance.mechanism->assembly_modes(instance.q);
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

std::vector<Instance> ch5_instances() {
  return shipped_instances("hexapod_ch5.yaml");
}
std::vector<Instance> genhexkins_instances() {
  return shipped_instances("hexapod_genhexkins.yaml");
}
std::vector<Instance> delta30_instances() {
  return shipped_instances("hexapod_ch3_delta30.yaml");
}

BENCHMARK_CAPTURE(BM_AssemblyModes, general_6_6, general_instances)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, symmetric_6_6, symmetric_instances)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, dietmaier_40_real, dietmaier_instance)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_ch3_delta30_6_6, delta30_instances)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_ch5_6_3_scan, ch5_instances)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssemblyModes, shipped_genhexkins_3_6_scan, genhexkins_instances)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
