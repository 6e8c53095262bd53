// pkm stiffness end to end on a 100 000-point CL program (goal < 5 s), for docs/PERFORMANCE.md: a
// 5-axis zig-zag finishing of the spherical cap of examples/programs/ball_end_5axis.cl (R 150 mm, tool axis
// on the normal) with 100 000 GOTOs, read, cut into points, every point's compliance, deflection and strut
// forces under a cutting load, points.csv and summary.json written. BM_StiffnessProgram100kCompensated adds
// the NC pre-compensation and the corrected CL program, in the same run for the ratio.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "bench_support.hpp"
#include "pipeline/stiffness_program.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

// 250 passes of 400 points over x ∈ [−28, 28], y ∈ [−15, 15] on the sphere z = √(R² − x² − y²) − R.
const std::string& cap_program_100k() {
  static const std::string path = [] {
    const fs::path file = fs::temp_directory_path() / "pkm_bench_cap_100k.cl";
    std::ofstream out(file);
    constexpr double kRadius = 150.0;
    constexpr int kPasses = 250, kPerPass = 400;
    out << "UNITS/MM\nMULTAX/ON\nRAPID\nGOTO/-28.0,-15.0,30.0,0.0,0.0,1.0\nFEDRAT/MMPM,1200.0\n";
    for (int p = 0; p < kPasses; ++p) {
      const double y = -15.0 + 30.0 * p / (kPasses - 1);
      for (int i = 0; i < kPerPass; ++i) {
        const double u = static_cast<double>(i) / (kPerPass - 1);
        const double x = p % 2 == 0 ? -28.0 + 56.0 * u : 28.0 - 56.0 * u;
        const double z = std::sqrt(kRadius * kRadius - x * x - y * y) - kRadius;
        out << fmt::format("GOTO/{:.4f},{:.4f},{:.4f},{:.7f},{:.7f},{:.7f}\n", x, y, z, x / kRadius,
                           y / kRadius, (z + kRadius) / kRadius);
      }
    }
    out << "FINI\n";
    return file.string();
  }();
  return path;
}

void run_stiffness_program(benchmark::State& state, bool compensate) {
  const Machine& machine = bench::ch5_hexapod();
  pipeline::StiffnessJob job;
  job.program_path = cap_program_100k();
  auto load = statics::parse_load_spec("tangential=600,normal=150,axial=80");
  if (!load) {
    state.SkipWithError(load.error().message.c_str());
    return;
  }
  job.load = *load;
  job.out_directory = (fs::temp_directory_path() / "pkm_bench_stiffness_program").string();
  if (compensate) job.compensated_path = job.out_directory + "/compensated.cl";
  long points = 0;
  for (auto _ : state) {
    auto result = pipeline::stiffness_program(machine, job);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      break;
    }
    points = result->statistics.points;
  }
  state.counters["points"] = static_cast<double>(points);
  fs::remove_all(job.out_directory);
}

void BM_StiffnessProgram100k(benchmark::State& state) {
  run_stiffness_program(state, false);
}
BENCHMARK(BM_StiffnessProgram100k)->Unit(benchmark::kSecond)->Iterations(3);

void BM_StiffnessProgram100kCompensated(benchmark::State& state) {
  run_stiffness_program(state, true);
}
BENCHMARK(BM_StiffnessProgram100kCompensated)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
