// The G-code interpreter's own speed (program/part_program.hpp), beside LinuxCNC's rs274
// (scripts/interpret-speed-compare.sh compares the two whole programs on the command line):
//
// BM_InterpretCamProgram: interpret_gcode on a generated 100 000-line CAM-like program (short G1 lines in
// X Y Z with four decimals, a tangent G2/G3 half circle every tenth block, a new F every hundredth), the
// program held in memory so that reading the file is not timed. Counters: lines_per_s, moves.
//
// BM_InterpretWhileLoop: a 100 000-iteration O-word while loop, with a G1 move in every iteration
// (motion = 1) or only the parameter arithmetic (motion = 0): the expression evaluator and the control flow,
// which CAM programs hardly use but hand-written and ngcgui programs do. Counters: iterations_per_s, moves.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "program/part_program.hpp"

namespace pkm {
namespace {

constexpr int kCamLines = 100'000;
constexpr int kLoopIterations = 100'000;

// Deterministic, no random numbers: the zigzag over a 50 mm field that a pocketing post writes.
std::string cam_program(int lines) {
  std::string text =
      "(bench_interpret: generated CAM-like program)\nG21 G90 G17 G94\nG0 Z5\nG0 X0 Y0\nG1 Z0 F800\n";
  text.reserve(static_cast<std::size_t>(lines) * 32);
  double x = 0.0;
  double y = 0.0;
  for (int i = 0; i < lines; ++i) {
    char block[96];
    const double z = -0.001 * (i % 500);
    if (i % 10 == 9) {
      // a half circle of radius 0.5 to the next row's start, alternating its direction
      const bool ccw = (i / 10) % 2 == 0;
      std::snprintf(block, sizeof block, "%s X%.4f Y%.4f Z%.4f I0 J0.5\n", ccw ? "G3" : "G2", x, y + 1.0, z);
      y += 1.0;
      if (y > 50.0) y = 0.0;
    } else {
      x = 0.25 * (i % 200) + 0.0001 * (i % 7);
      std::snprintf(block, sizeof block, "G1 X%.4f Y%.4f Z%.4f%s\n", x, y, z,
                    i % 100 == 0 ? (i % 200 == 0 ? " F1200" : " F900") : "");
    }
    text.append(block);
  }
  text.append("G0 Z5\nM2\n");
  return text;
}

std::string while_program(int iterations, bool motion) {
  std::string text = "G21 G90 F1000\n#1=0\no100 while [#1 LT " + std::to_string(iterations) + "]\n";
  if (motion) text.append("G1 X[#1 MOD 100]\n");
  text.append("#1=[#1+1]\no100 endwhile\nM2\n");
  return text;
}

void run(benchmark::State& state, const std::string& text, const char* name, double per_run,
         const char* per_second) {
  program::InterpretOptions options;
  std::size_t moves = 0;
  for (auto _ : state) {
    auto program = program::interpret_gcode(text, name, options);
    if (!program) {
      state.SkipWithError(program.error().message.c_str());
      return;
    }
    moves = program->moves.size();
    benchmark::DoNotOptimize(program->moves.data());
  }
  state.counters[per_second] =
      benchmark::Counter(per_run * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["moves"] = static_cast<double>(moves);
}

void BM_InterpretCamProgram(benchmark::State& state) {
  static const std::string text = cam_program(kCamLines);
  run(state, text, "cam.ngc", kCamLines, "lines_per_s");
}
BENCHMARK(BM_InterpretCamProgram)->Unit(benchmark::kMillisecond);

void BM_InterpretWhileLoop(benchmark::State& state) {
  const bool motion = state.range(0) != 0;
  const std::string text = while_program(kLoopIterations, motion);
  run(state, text, motion ? "while_motion.ngc" : "while.ngc", kLoopIterations, "iterations_per_s");
}
BENCHMARK(BM_InterpretWhileLoop)->Arg(1)->Arg(0)->ArgName("motion")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
