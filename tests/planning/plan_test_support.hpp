#pragma once
// Helpers for the planning tests: interpret G-code text for a machine and run a plan through the servo
// stream.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "planning/motion_plan.hpp"
#include "planning/run_monitor.hpp"
#include "planning/servo_stream.hpp"
#include "program/part_program.hpp"

namespace pkm::test {

inline program::CanonicalProgram gcode_for(const Machine& machine, const std::string& text,
                                           const std::string& name = "test.ngc") {
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions options;
  options.start_mm = start.start_mm;
  options.start_abc_deg = start.start_abc_deg;
  auto program = program::interpret_gcode(text, name, options);
  if (!program) {
    ADD_FAILURE() << program.error().message;
    throw std::runtime_error(program.error().message);
  }
  return std::move(program.value());
}

inline planning::MotionPlan plan_or_fail(const Machine& machine, const program::CanonicalProgram& program,
                                         const planning::PlanOptions& options = {}) {
  auto plan = planning::plan_motion(machine, program, options);
  if (!plan) {
    ADD_FAILURE() << plan.error().message;
    throw std::runtime_error(plan.error().message);
  }
  return std::move(plan.value());
}

/// Every tick of a plan, with the monitor's summary.
struct Run {
  std::vector<planning::ServoTick> ticks;
  planning::RunSummary summary;
};

inline Run run_plan(const Machine& machine, const planning::MotionPlan& plan, double override_pct = 100.0,
                    bool path_error = true) {
  Run run;
  planning::ServoStream stream(plan, machine);
  planning::RunMonitor monitor(plan, machine, override_pct, path_error);
  planning::ServoTick tick;
  while (stream.next(tick)) {
    monitor.add(tick);
    run.ticks.push_back(tick);
  }
  EXPECT_FALSE(stream.error().has_value()) << stream.error()->message;
  run.summary = monitor.summary();
  return run;
}

/// Actuator limits at the servo rate, path speed ≤ programmed feed × override, path acceleration and jerk
/// within the machine's, continuity, start and end at rest, the end exactly at the path's end, a small path
/// error.
inline void expect_motion_invariants(const Machine& machine, const planning::MotionPlan& plan, const Run& run,
                                     const std::string& label) {
  const double h = plan.period_s;
  ASSERT_GE(run.ticks.size(), 2u) << label;
  // Actuator limits at the servo rate.
  EXPECT_LE(run.summary.max_actuator_speed, *machine.limits.speed) << label;
  EXPECT_LE(run.summary.max_actuator_accel, *machine.limits.accel) << label;
  // Path speed ≤ programmed feed × override; path acceleration and jerk within the machine's.
  EXPECT_LE(run.summary.max_feed_ratio, 1.0 + 1e-6) << label;
  EXPECT_LE(run.summary.max_path_accel, machine.motion.path_accel_mm_s2 * (1 + 1e-6)) << label;
  EXPECT_LE(run.summary.max_path_jerk, machine.motion.path_jerk_mm_s3 * (1 + 1e-6)) << label;
  // Continuity: no tick moves an actuator further than its speed limit allows in one period, and the tool
  // point never jumps.
  for (std::size_t k = 1; k < run.ticks.size(); ++k) {
    const double jump = (run.ticks[k].pose.position_mm - run.ticks[k - 1].pose.position_mm).norm();
    ASSERT_LE(jump, machine.motion.rapid_mm_min / 60.0 * h * (1 + 1e-9) + 1e-12) << label << " tick " << k;
  }
  // Starts and ends at rest, exactly at the program's end.
  EXPECT_EQ(run.ticks.front().path_speed, 0.0);
  EXPECT_NEAR(run.ticks.back().path_speed, 0.0, 1e-6) << label;
  const path::PathPoint end = plan.path.end_point();
  EXPECT_EQ((run.ticks.back().pose.position_mm - end.position_mm).norm(), 0.0) << label;
  EXPECT_LT(run.summary.max_path_error_mm, 1e-3) << label;
}

}  // namespace pkm::test
