// Planning throughput on a 100 000-line generated program (CAM-like: short G1 segments 0.2–2 mm, G2/G3 arcs,
// feeds 500–3000 mm/min, small A/B tilts) on the ch5 hexapod, for docs/PERFORMANCE.md:
//   Interpret     G-code text → canonical moves
//   Plan          interpret + path with corner blends + speed profile (IK and limits at every sample)
//   ServoOutput   the planned motion at 1 kHz: filter, path evaluation and IK per tick (no files written)
//   Streamed      the same through the plan's look-ahead window as pkm plan runs it: the plan made once to
//                 its end keeping nothing, then again while the servo stream pulls and releases it
//   SpeedProfile  the speed passes alone on the plan's samples: over the whole program at once (erosion,
//                 forward, backward) against through the default look-ahead window
// Counters: blocks/s, ticks/s, real-time factor (motion seconds per compute second) and peak memory.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "bench_support.hpp"
#include "io/machine_file.hpp"
#include "planning/lookahead_profile.hpp"
#include "planning/motion_plan.hpp"
#include "planning/plan_producer.hpp"
#include "planning/servo_stream.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

constexpr int kLines = 100000;

const Machine& machine() {
  return bench::ch5_hexapod();
}

/// A deterministic CAM-like program: a random walk of short moves inside ±50 mm (XY) and ±10 mm (Z).
const std::string& long_program() {
  static const std::string text = [] {
    std::mt19937_64 rng(20261121);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::string out = "G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F500\n";
    out.reserve(kLines * 40);
    double x = 0, y = 0, z = 0, heading = 0;
    for (int line = 3; line < kLines - 1; ++line) {
      heading += (u(rng) - 0.5) * 0.3;
      const double step = 0.2 + 1.8 * u(rng);
      // Turn back towards the centre near the edge of the box.
      if (std::hypot(x, y) > 45.0) heading = std::atan2(-y, -x) + (u(rng) - 0.5);
      const double feed = 500.0 + 2500.0 * u(rng);
      if (u(rng) < 0.1) {  // a short arc, radius 2–10 mm, turning up to 60°
        const double r = 2.0 + 8.0 * u(rng), turn = (u(rng) < 0.5 ? 1 : -1) * u(rng) * 1.0;
        const double side = turn > 0 ? 1.0 : -1.0;
        const double cx = x - side * r * std::sin(heading), cy = y + side * r * std::cos(heading);
        const double start = std::atan2(y - cy, x - cx), end = start + turn;
        const double nx = cx + r * std::cos(end), ny = cy + r * std::sin(end);
        out += fmt::format("G{} X{:.4f} Y{:.4f} I{:.4f} J{:.4f} F{:.0f}\n", turn > 0 ? 3 : 2, nx, ny, cx - x,
                           cy - y, feed);
        x = nx, y = ny, heading += turn;
      } else {
        x += step * std::cos(heading);
        y += step * std::sin(heading);
        z = std::clamp(z + (u(rng) - 0.5) * 0.2, -10.0, 10.0);
        const double a = 3.0 * std::sin(line * 1e-3), b = 3.0 * std::cos(line * 1.3e-3);
        out += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f} A{:.3f} B{:.3f} F{:.0f}\n", x, y, z, a, b, feed);
      }
    }
    out += "M2\n";
    return out;
  }();
  return text;
}

program::InterpretOptions start_options() {
  const planning::ProgramStart start = planning::program_start(machine());
  program::InterpretOptions options;
  options.start_mm = start.start_mm;
  options.start_abc_deg = start.start_abc_deg;
  return options;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

void BM_Interpret100k(benchmark::State& state) {
  const std::string& text = long_program();
  for (auto _ : state) {
    auto program = program::interpret_gcode(text, "long.ngc", start_options());
    if (!program) state.SkipWithError(program.error().message.c_str());
    benchmark::DoNotOptimize(program);
  }
  state.counters["blocks_per_s"] = benchmark::Counter(kLines, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Interpret100k)->Unit(benchmark::kMillisecond);

// One CL statement continued with '$' over N lines (a malformed CAM file the bad-input catalogue holds): the
// reader must stay linear in N (it was quadratic once, 12.8 s at 200 000 lines). Complexity fit: O(N).
void BM_ReadClContinuedStatement(benchmark::State& state) {
  std::string text = "UNITS/MM\nFEDRAT/100\nGOTO/1 $\n";
  for (long i = 0; i < state.range(0); ++i) text += ",0 $\n";
  text += "\nFINI\n";
  for (auto _ : state) {
    auto program = program::read_cl_data(text, "continued.cl", start_options());
    benchmark::DoNotOptimize(program);
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_ReadClContinuedStatement)
    ->RangeMultiplier(4)
    ->Range(12500, 200000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

void BM_Plan100k(benchmark::State& state) {
  const std::string& text = long_program();
  double duration = 0.0;
  std::size_t samples = 0;
  for (auto _ : state) {
    auto program = program::interpret_gcode(text, "long.ngc", start_options());
    if (!program) {
      state.SkipWithError(program.error().message.c_str());
      break;
    }
    auto plan = planning::plan_motion(machine(), *program, {});
    if (!plan) {
      state.SkipWithError(plan.error().message.c_str());
      break;
    }
    duration = plan->duration_s;
    samples = plan->samples.size();
  }
  state.counters["blocks_per_s"] = benchmark::Counter(kLines, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["motion_s"] = duration;
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["peak_rss_MB"] = peak_rss_mb();
}
BENCHMARK(BM_Plan100k)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ServoOutput(benchmark::State& state) {
  auto program = program::interpret_gcode(long_program(), "long.ngc", start_options());
  auto plan = planning::plan_motion(machine(), *program, {});
  if (!plan) {
    state.SkipWithError(plan.error().message.c_str());
    return;
  }
  long ticks = 0;
  for (auto _ : state) {
    planning::ServoStream stream(*plan, machine());
    planning::ServoTick tick;
    ticks = 0;
    while (stream.next(tick)) ++ticks;
    benchmark::DoNotOptimize(tick);
  }
  state.counters["ticks_per_s"] =
      benchmark::Counter(static_cast<double>(ticks), benchmark::Counter::kIsIterationInvariantRate);
  // Motion seconds produced per compute second: ≥ 10 is the goal.
  state.counters["realtime_factor"] =
      benchmark::Counter(plan->duration_s, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["motion_s"] = plan->duration_s;
}
BENCHMARK(BM_ServoOutput)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_ServoOutputStreamed(benchmark::State& state) {
  auto program = program::interpret_gcode(long_program(), "long.ngc", start_options());
  long ticks = 0;
  std::size_t peak_samples = 0, peak_segments = 0, samples = 0;
  for (auto _ : state) {
    auto streamed = planning::start_streamed_plan(machine(), *program, {});
    if (!streamed) {
      state.SkipWithError(streamed.error().message.c_str());
      return;
    }
    planning::ServoStream stream((*streamed)->plan, machine(), (*streamed)->source.get());
    planning::ServoTick tick;
    ticks = 0;
    while (stream.next(tick)) ++ticks;
    benchmark::DoNotOptimize(tick);
    peak_samples = (*streamed)->source->peak_samples();
    peak_segments = (*streamed)->source->peak_segments();
    samples = (*streamed)->plan.statistics.samples;
  }
  state.counters["ticks_per_s"] =
      benchmark::Counter(static_cast<double>(ticks), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["peak_window_samples"] = static_cast<double>(peak_samples);
  state.counters["peak_window_segments"] = static_cast<double>(peak_segments);
}
BENCHMARK(BM_ServoOutputStreamed)->Unit(benchmark::kMillisecond)->Iterations(1);

/// The plan's samples and the move of each, planned once for both speed-profile benchmarks.
struct ProfileInput {
  planning::ProfileSamples samples;
  std::vector<int> move;
  planning::LookaheadSettings window;
};
const ProfileInput& profile_input() {
  static const ProfileInput input = [] {
    ProfileInput in;
    auto program = program::interpret_gcode(long_program(), "long.ngc", start_options());
    auto plan = planning::plan_motion(machine(), *program, {});
    in.samples = plan->samples;
    for (int segment : plan->sample_segment) in.move.push_back(plan->path.segments[segment].move);
    const planning::PlanOptions defaults;
    const MotionSettings& motion = machine().motion;
    in.window.filter_window_s = plan->statistics.filter_time_s;
    in.window.fastest_cap =
        std::max({motion.rapid_mm_min, motion.max_feed_mm_min, motion.angular_feed_deg_min}) / 60.0;
    in.window.max_length = defaults.lookahead_mm;
    in.window.max_moves = defaults.lookahead_moves;
    in.window.max_samples = defaults.lookahead_samples;
    return in;
  }();
  return input;
}

void BM_SpeedProfileWhole(benchmark::State& state) {
  const ProfileInput& in = profile_input();
  for (auto _ : state) {
    planning::ProfileSamples samples = in.samples;
    planning::erode_caps(samples, in.window.filter_window_s, 0.0);
    planning::plan_speeds(samples);
    benchmark::DoNotOptimize(samples.speed.data());
  }
  state.counters["samples"] = static_cast<double>(in.samples.size());
}
BENCHMARK(BM_SpeedProfileWhole)->Unit(benchmark::kMillisecond);

void BM_SpeedProfileWindow(benchmark::State& state) {
  const ProfileInput& in = profile_input();
  long binding = 0;
  for (auto _ : state) {
    planning::ProfileSamples samples = in.samples;
    binding = planning::plan_speeds_lookahead(samples, in.move, in.window);
    benchmark::DoNotOptimize(samples.speed.data());
  }
  state.counters["samples"] = static_cast<double>(in.samples.size());
  state.counters["binding"] = static_cast<double>(binding);
}
BENCHMARK(BM_SpeedProfileWindow)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
