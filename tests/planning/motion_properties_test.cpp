// Invariants of planned motion, on random programs and on the machine's own limits: actuator speeds and
// accelerations within the machine file's limits (sampled at the servo rate), path speed never above the
// programmed feed, path acceleration and jerk within the machine's, continuity, and the end exactly at the
// program's end.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "path/corner_blend.hpp"
#include "plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

/// A random 3- to 5-axis program around program zero: lines and arcs in every plane, helices, tilts.
std::string random_program(std::mt19937_64& rng, int moves) {
  std::string text = "G21 G90 G17\nG0 X0 Y0 Z0\n";
  Eigen::Vector3d p(0, 0, 0);
  for (int m = 0; m < moves; ++m) {
    const double feed = test::uniform(rng, 200.0, 5000.0);
    const int kind = static_cast<int>(test::uniform(rng, 0.0, 10.0));
    if (kind < 6) {
      Eigen::Vector3d q(test::uniform(rng, -40, 40), test::uniform(rng, -40, 40),
                        test::uniform(rng, -20, 20));
      if (kind == 0) q = p + Eigen::Vector3d(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), 0.0);
      const double a = test::uniform(rng, -5, 5), b = test::uniform(rng, -5, 5);
      text += fmt::format("G{} X{:.4f} Y{:.4f} Z{:.4f} A{:.3f} B{:.3f} F{:.1f}\n", kind == 1 ? 0 : 1, q.x(),
                          q.y(), q.z(), a, b, feed);
      p = q;
    } else {
      // An arc of radius 5…20 mm in a random principal plane, ending a quarter to a full turn later.
      const int plane = static_cast<int>(test::uniform(rng, 0.0, 3.0));
      const int i0 = plane == 0 ? 0 : plane == 1 ? 2 : 1;  // first in-plane axis (XY: X, ZX: Z, YZ: Y)
      const int i1 = plane == 0 ? 1 : plane == 1 ? 0 : 2;
      const double r = test::uniform(rng, 5.0, 20.0), start = test::uniform(rng, 0, 2 * M_PI);
      const double sweep = test::uniform(rng, 0.5, 6.0);
      Eigen::Vector3d centre = p;
      centre[i0] -= r * std::cos(start);
      centre[i1] -= r * std::sin(start);
      Eigen::Vector3d end = centre;
      end[i0] += r * std::cos(start + sweep);
      end[i1] += r * std::sin(start + sweep);
      const int axis = 3 - i0 - i1;
      end[axis] = p[axis] + test::uniform(rng, -3, 3);  // a helix
      const char* names = "XYZ";
      const char* offsets = "IJK";
      text += fmt::format("G{} G3 X{:.6f} Y{:.6f} Z{:.6f} {}{:.6f} {}{:.6f} F{:.1f}\n", 17 + plane, end.x(),
                          end.y(), end.z(), offsets[i0], centre[i0] - p[i0], offsets[i1], centre[i1] - p[i1],
                          feed);
      (void)names;
      p = end;
    }
  }
  return text + "M2\n";
}

TEST(PlanProperties, RandomProgramsStayWithinEveryLimit) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(2026);
  for (int trial = 0; trial < 8; ++trial) {
    const std::string text = random_program(rng, 25);
    const auto program = test::gcode_for(machine, text, fmt::format("random{}.ngc", trial));
    const double override_pct = trial % 3 == 0 ? 150.0 : trial % 3 == 1 ? 100.0 : 40.0;
    planning::PlanOptions options;
    options.override_pct = override_pct;
    options.rate_hz = trial % 2 ? 1000.0 : 2000.0;
    const auto plan = test::plan_or_fail(machine, program, options);
    const auto run = test::run_plan(machine, plan, override_pct);
    test::expect_motion_invariants(machine, plan, run, fmt::format("trial {}:\n{}", trial, text));
    // The programmed end of the last move, in the base frame.
    const Eigen::Vector3d last = program.moves.back().end_mm + machine.motion.program_origin_mm;
    EXPECT_NEAR((run.ticks.back().pose.position_mm - last).norm(), 0.0, 1e-9) << "trial " << trial;
  }
}

class PlanOtherMechanisms : public testing::TestWithParam<const char*> {};

TEST_P(PlanOtherMechanisms, PlanWithinTheirOwnLimits) {
  const Machine machine = test::machine_from_example(std::string("examples/machines/") + GetParam());
  // Each machine moves only what it controls: a tripod Z, A, B; a tricept X, Y, Z; the others all six.
  const std::string name = GetParam();
  const std::string text =
      name == "tripod.yaml"
          ? "G21 G90 G17\nG0 Z0 A0 B0\nG1 Z-3 A2 F1200\nG1 B-2\nG1 Z5 A-2 B2 F2000\nG1 Z0 A0 B0\nM2\n"
          : fmt::format(
                "G21 G90 G17\nG0 X0 Y0 Z0\nG1 X10 Y5 Z-3 F1200\nG2 X10 Y-5 I0 J-5\nG1 X-10{}\n"
                "G3 X-10 Y5 I0 J5 F2000\nG1 X0 Y0 Z0{}\nM2\n",
                name == "tricept.yaml" ? "" : " A2 B-2", name == "tricept.yaml" ? "" : " A0 B0");
  const auto program = test::gcode_for(machine, text, GetParam());
  const auto plan = test::plan_or_fail(machine, program);
  const auto run = test::run_plan(machine, plan);
  test::expect_motion_invariants(machine, plan, run, GetParam());
  EXPECT_EQ(run.summary.fk_failures, 0);
}

INSTANTIATE_TEST_SUITE_P(Examples, PlanOtherMechanisms,
                         testing::Values("tricept.yaml", "tripod.yaml", "hexaglide.yaml", "rotopod.yaml",
                                         "hexapod_refined.yaml"));

TEST(PlanProperties, APlanarMachineTakesCAsItsPlatformAngle) {
  Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  machine.limits.speed = 100.0;
  machine.limits.accel = 1000.0;
  const auto program =
      test::gcode_for(machine, "G0 X40 Y0 C15\nG2 X40 Y0 I-40 J0 C20 F600\nM2\n", "planar.ngc");
  const auto plan = test::plan_or_fail(machine, program);
  const auto run = test::run_plan(machine, plan);
  test::expect_motion_invariants(machine, plan, run, "planar3");
  const Pose& end = run.ticks.back().pose;
  EXPECT_NEAR(std::atan2(end.rotation(1, 0), end.rotation(0, 0)), 20.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(end.position_mm.x(), 40.0, 1e-9);
  const auto tilted = test::gcode_for(machine, "G1 X10 A5 F600\n", "tilted.ngc");
  auto refused = planning::plan_motion(machine, tilted, {});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("tilted.ngc:1:"), std::string::npos) << refused.error().message;
}

TEST(PlanProperties, CornerBlendsStayWithinTheTolerance) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(99);
  for (double tolerance : {0.002, 0.01, 0.1}) {
    const auto program = test::gcode_for(machine, random_program(rng, 30));
    planning::PlanOptions options;
    options.path_tolerance_mm = tolerance;
    const auto plan = test::plan_or_fail(machine, program, options);
    int blends = 0;
    for (int k = 0; k < static_cast<int>(plan.path.segments.size()); ++k) {
      if (!plan.path.segments[k].is_blend()) continue;
      ++blends;
      EXPECT_LE(path::blend_deviation_mm(plan.path, k), tolerance * (1 + 1e-6)) << "segment " << k;
    }
    EXPECT_GT(blends, 5);
  }
}

TEST(PlanProperties, PathIsContinuousInArcLengthAcrossSegments) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(5);
  const auto program = test::gcode_for(machine, random_program(rng, 40));
  const auto plan = test::plan_or_fail(machine, program);
  const auto& segments = plan.path.segments;
  for (std::size_t k = 1; k < segments.size(); ++k) {
    EXPECT_NEAR(segments[k].s_start, segments[k - 1].s_start + segments[k - 1].length, 1e-9);
    const path::PathPoint a = plan.path.evaluate(static_cast<int>(k - 1), segments[k].s_start);
    const path::PathPoint b = plan.path.evaluate(static_cast<int>(k), segments[k].s_start);
    EXPECT_LT((a.position_mm - b.position_mm).norm(), 1e-9) << k;
    EXPECT_LT(a.rotation.angularDistance(b.rotation), 1e-9) << k;
    EXPECT_GT(segments[k].line, 0);
  }
}

TEST(PlanProperties, TheFeedDropsWhereTheActuatorsDemandIt) {
  // The same line with struts ten times slower: the planner lowers the feed, the struts stay within limits.
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(machine, "G0 X-50 Y0 Z0\nG1 X50 F6000\nG2 X50 Y0 I-20 J0\nM2\n");
  const auto fast = test::plan_or_fail(machine, program);
  machine.limits.speed = 10.0;
  machine.limits.accel = 200.0;
  const auto slow = test::plan_or_fail(machine, program);
  const auto run = test::run_plan(machine, slow);
  EXPECT_LE(run.summary.max_actuator_speed, 10.0);
  EXPECT_LE(run.summary.max_actuator_accel, 200.0);
  EXPECT_GT(run.summary.max_actuator_speed, 8.0) << "the struts should be used near their limit";
  EXPECT_GT(slow.statistics.actuator_limited_fraction, 0.5);
  EXPECT_GT(slow.duration_s, 2.0 * fast.duration_s);
}

TEST(PlanProperties, OverrideScalesTheFeedWithinTheAccelerationLimits) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(machine, "G0 X-50 Y0 Z0\nG1 X50 F1200\nM2\n");
  double previous_duration = 1e9;
  for (double override_pct : {25.0, 50.0, 100.0, 200.0}) {
    planning::PlanOptions options;
    options.override_pct = override_pct;
    const auto plan = test::plan_or_fail(machine, program, options);
    const auto run = test::run_plan(machine, plan, override_pct);
    double top = 0.0;
    for (const auto& tick : run.ticks) {
      if (tick.line == 2) top = std::max(top, tick.path_speed);
    }
    EXPECT_NEAR(top, 20.0 * override_pct / 100.0, 1e-6) << override_pct;
    EXPECT_LE(run.summary.max_path_accel, machine.motion.path_accel_mm_s2 * (1 + 1e-6));
    EXPECT_LT(plan.duration_s, previous_duration);
    previous_duration = plan.duration_s;
  }
}

TEST(PlanErrors, LimitViolationsNameTheProgramLineAndTheLimit) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  // Line 3 climbs 500 mm: the struts leave their 900 mm range on the way.
  const auto program = test::gcode_for(machine, "G0 X0 Y0 Z0\nG1 X10 F1000\nG1 Z500\nM2\n", "climb.ngc");
  auto plan = planning::plan_motion(machine, program, {});
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().code, ErrorCode::limit_exceeded);
  EXPECT_NE(plan.error().message.find("climb.ngc:3:"), std::string::npos) << plan.error().message;
  EXPECT_NE(plan.error().message.find("actuator_max"), std::string::npos) << plan.error().message;
  EXPECT_NE(plan.error().message.find("hexapod_ch5.yaml:"), std::string::npos) << plan.error().message;
}

TEST(PlanErrors, UnreachablePosesNameTheLine) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(machine, "G0 X0 Y0 Z0\nG1 X2000 F1000\nM2\n", "far.ngc");
  auto plan = planning::plan_motion(machine, program, {});
  ASSERT_FALSE(plan.ok());
  EXPECT_NE(plan.error().message.find("far.ngc:2:"), std::string::npos) << plan.error().message;
}

TEST(PlanErrors, AProgramWithoutMotionIsAnError) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(machine, "G21 G90\nG4 P1\nM2\n", "still.ngc");
  auto plan = planning::plan_motion(machine, program, {});
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().code, ErrorCode::bad_input);
  EXPECT_NE(plan.error().message.find("still.ngc"), std::string::npos);
}

TEST(PlanErrors, BadOptionsAreRejected) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(machine, "G1 X1 F100\n");
  for (double override_pct : {0.0, -5.0, 250.0}) {
    planning::PlanOptions options;
    options.override_pct = override_pct;
    auto plan = planning::plan_motion(machine, program, options);
    ASSERT_FALSE(plan.ok());
    EXPECT_EQ(plan.error().code, ErrorCode::bad_input);
    EXPECT_NE(plan.error().message.find("override"), std::string::npos);
  }
  planning::PlanOptions options;
  options.rate_hz = 0.0;
  EXPECT_FALSE(planning::plan_motion(machine, program, options).ok());
}

}  // namespace
}  // namespace pkm
