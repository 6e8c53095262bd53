#pragma once
// Helpers for the interpolation tests: the chapter-5 test line of Smirnov 2019 on its test hexapod, starting
// exactly at (−50, 0, 700) (§5.2, §5.2.3), as a path with constant-speed timing (§5.2.3 and §5.2.5, without
// acceleration) or planned like any program.
#include <string>

#include "interpolation/interpolate_run.hpp"
#include "interpolation/methods/ideal_timing.hpp"
#include "planning/plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm::test {

/// A program that starts where `start_mm` (program coordinates) says, not at the machine's home.
inline program::CanonicalProgram gcode_from(const Machine& machine, const std::string& text,
                                            const Eigen::Vector3d& start_mm) {
  program::InterpretOptions options;
  options.start_mm = start_mm;
  options.start_abc_deg = planning::program_start(machine).start_abc_deg;
  auto program = program::interpret_gcode(text, "test.ngc", options);
  if (!program) {
    ADD_FAILURE() << program.error().message;
    throw std::runtime_error(program.error().message);
  }
  return std::move(program.value());
}

/// The ch5 line (−50, 0, 700) → (50, 0, 700) at 50 mm/s, as a planned path (the program's Z0 is z = 700).
inline planning::MotionPlan ch5_line_plan(const Machine& machine, double period_s) {
  const auto program = gcode_from(machine, "G21 G90 G17\nG1 X50 Y0 Z0 F3000\nM2\n", {-50.0, 0.0, 0.0});
  planning::PlanOptions options;
  options.rate_hz = 1.0 / period_s;
  return plan_or_fail(machine, program, options);
}

inline interpolation::InterpolateSummary interpolate_or_fail(
    const Machine& machine, const path::Path& path, const interpolation::IdealTiming& timing,
    const interpolation::InterpolateOptions& options,
    const std::vector<interpolation::StepSink*>& sinks = {}) {
  auto summary = interpolation::interpolate(machine, path, timing, options, sinks, "test.ngc");
  if (!summary) {
    ADD_FAILURE() << to_string(summary.error().code) << ": " << summary.error().message;
    throw std::runtime_error(summary.error().message);
  }
  return std::move(summary.value());
}

}  // namespace pkm::test
