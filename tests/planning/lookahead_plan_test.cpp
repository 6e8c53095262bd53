// A whole plan through a look-ahead window that binds: CAM-like short moves along a long fast straight, then
// a reversal, with a window of a few moves that cannot hold the braking distance.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm::planning {
namespace {

/// 160 moves of 0.5 mm at the machine's fastest feed along X, then straight back: a corner of 180°.
std::string straight_then_reversal() {
  std::string text = "G21 G90 G17 G94\nG0 X-40 Y0 Z0\nG1 F6000\n";
  for (int k = 1; k <= 160; ++k) text += fmt::format("G1 X{:.1f}\n", -40.0 + 0.5 * k);
  text += "G1 X-40\nM2\n";
  return text;
}

TEST(LookaheadPlan, ABindingWindowSlowsTheStraightAndHoldsEveryLimitAtEveryTick) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const program::CanonicalProgram program = test::gcode_for(machine, straight_then_reversal());
  const MotionPlan whole = test::plan_or_fail(machine, program);
  EXPECT_EQ(whole.statistics.lookahead_binding, 0);

  PlanOptions options;
  options.lookahead_moves = 4;  // 2 mm of path: braking from 100 mm/s at 1000 mm/s² takes 5 mm
  const MotionPlan windowed = test::plan_or_fail(machine, program, options);
  EXPECT_GT(windowed.statistics.lookahead_binding, 0);
  EXPECT_GT(windowed.duration_s, whole.duration_s);
  const test::Run run = test::run_plan(machine, windowed);
  test::expect_motion_invariants(machine, windowed, run, "window of 4 moves");
  const test::Run whole_run = test::run_plan(machine, whole);
  EXPECT_LT(run.summary.max_path_speed, whole_run.summary.max_path_speed);
}

TEST(LookaheadPlan, TheDefaultWindowPlansTheStraightAsTheUnboundedOne) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const program::CanonicalProgram program = test::gcode_for(machine, straight_then_reversal());
  const MotionPlan bounded = test::plan_or_fail(machine, program);
  PlanOptions unbounded;
  unbounded.lookahead_mm = std::numeric_limits<double>::infinity();
  unbounded.lookahead_moves = std::numeric_limits<int>::max();
  unbounded.lookahead_samples = std::numeric_limits<std::size_t>::max();
  const MotionPlan whole = test::plan_or_fail(machine, program, unbounded);
  ASSERT_EQ(bounded.samples.size(), whole.samples.size());
  for (std::size_t i = 0; i < whole.samples.size(); ++i)
    ASSERT_EQ(bounded.samples.speed[i], whole.samples.speed[i]);
  EXPECT_EQ(bounded.duration_s, whole.duration_s);
}

}  // namespace
}  // namespace pkm::planning
