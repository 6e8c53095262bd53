// Redundancy laws (Smirnov 2019, chapter 3), for docs/PERFORMANCE.md: time per path point of the greedy
// per-step law and of the whole-path solver, on the dissertation's circles. Goals: greedy three-angle hexapod
// law under 50 µs per point; whole-path solver under 1 s for a 1000-point path.
//   Greedy/<law>/<machine>   greedy solve only; counter us_per_point
//   WholePath/<law>/...      whole-path solve from the greedy solution, 1000 points; counter s_per_path
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"
#include "redundancy/optimize_program.hpp"

namespace pkm {
namespace {

Machine load_example(const std::string& name) {
  auto loaded =
      load_machine_file((std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines" / name).string());
  if (!loaded) throw std::runtime_error(loaded.error().message);
  return std::move(loaded.value());
}

const Machine& hexapod() {
  static const Machine m = load_example("hexapod_ch3_delta30.yaml");
  return m;
}

const Machine& planar() {
  static const Machine m = load_example("planar3.yaml");
  return m;
}

program::CanonicalProgram circle(const Machine& machine, double radius_mm, double z_mm, double c_deg) {
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions options;
  options.start_mm = start.start_mm;
  options.start_abc_deg = start.start_abc_deg;
  auto program = program::interpret_gcode(fmt::format("G0 X{} Y0 Z{} C{}\nG3 X{} Y0 I{} J0 F600\nM2\n",
                                                      radius_mm, z_mm, c_deg, radius_mm, -radius_mm),
                                          "circle.ngc", options);
  if (!program) throw std::runtime_error(program.error().message);
  return std::move(program.value());
}

void run(benchmark::State& state, const Machine& machine, const program::CanonicalProgram& program,
         redundancy::OptimizeOptions options) {
  double greedy_s = 0.0;
  double whole_s = 0.0;
  std::size_t points = 0;
  for (auto _ : state) {
    auto result = redundancy::optimize_program(program, machine, options);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      return;
    }
    greedy_s += result->greedy.seconds;
    if (result->whole_path) whole_s += result->whole_path->seconds;
    points = result->points.points.size();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["points"] = static_cast<double>(points);
  state.counters["greedy_us_per_point"] = 1e6 * greedy_s / n / static_cast<double>(points);
  if (options.solver == redundancy::Solver::global) {
    state.counters["whole_path_s"] = whole_s / n;
    state.counters["whole_path_us_per_point"] = 1e6 * whole_s / n / static_cast<double>(points);
  }
}

redundancy::OptimizeOptions options_for(redundancy::Law law, redundancy::FreeSet free,
                                        redundancy::Solver solver, double step_mm,
                                        std::array<double, 2> bounds) {
  redundancy::OptimizeOptions options;
  options.law.law = law;
  options.free = free;
  options.solver = solver;
  options.step_mm = step_mm;
  options.bounds_deg = bounds;
  options.loads = *statics::parse_load_spec("tangential=1000,normal=100,cutter_radius=5,contact=right");
  return options;
}

// The hexapod circle of Smirnov 2019, §3.5.1 (R 50 mm at z 700 mm), 1000 points.
constexpr double kHexapodStepMm = 2.0 * std::numbers::pi * 50.0 / 1000.0;

void BM_HexapodThreeAngles(benchmark::State& state) {
  const auto law = static_cast<redundancy::Law>(state.range(0));
  const auto solver = state.range(1) != 0 ? redundancy::Solver::global : redundancy::Solver::greedy;
  run(state, hexapod(), circle(hexapod(), 50.0, 700.0, 0.0),
      options_for(law, redundancy::FreeSet::all, solver, kHexapodStepMm, {-10.0, 10.0}));
}
BENCHMARK(BM_HexapodThreeAngles)
    ->ArgNames({"law", "global"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

void BM_HexapodSpin(benchmark::State& state) {
  const auto law = static_cast<redundancy::Law>(state.range(0));
  run(state, hexapod(), circle(hexapod(), 50.0, 700.0, 0.0),
      options_for(law, redundancy::FreeSet::spin, redundancy::Solver::global, kHexapodStepMm, {-10.0, 10.0}));
}
BENCHMARK(BM_HexapodSpin)->ArgName("law")->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(3);

// The planar circle of Smirnov 2019, §3.4.1–3.4.2 (R 40 mm, 1° steps), φ in 5…30°.
void BM_PlanarPhi(benchmark::State& state) {
  const auto law = static_cast<redundancy::Law>(state.range(0));
  run(state, planar(), circle(planar(), 40.0, 0.0, 15.0),
      options_for(law, redundancy::FreeSet::spin, redundancy::Solver::global, 40.0 * std::numbers::pi / 180.0,
                  {5.0, 30.0}));
}
BENCHMARK(BM_PlanarPhi)->ArgName("law")->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
