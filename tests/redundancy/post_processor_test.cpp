// The post-processor (Smirnov 2019, §3.6): the written program means the chosen free coordinates, runs
// through the planner without limit violations, and its machining time at strut speed limits drops by the
// ratio the increment law predicts.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "program/gcode_writer.hpp"
#include "redundancy_test_support.hpp"

namespace pkm::test {
namespace {

using redundancy::Law;

program::CanonicalProgram reinterpret(const Machine& machine, const program::CanonicalProgram& optimized) {
  auto text = program::write_gcode(optimized, {});
  if (!text) {
    ADD_FAILURE() << text.error().message;
    throw std::runtime_error(text.error().message);
  }
  return gcode_for(machine, *text, "optimized.ngc");
}

TEST(PostProcessor, WrittenProgramCarriesTheChosenAngles) {
  const Machine machine = machine_from_text(ch3_hexapod_text(30.0), "ch3_hexapod.yaml");
  const auto program = gcode_for(machine, circle_program(50.0, 700.0));
  redundancy::OptimizeOptions options;
  options.free = redundancy::FreeSet::all;
  options.step_mm = 2.0;
  options.bounds_deg = redundancy::FreeBounds{{-10.0, 10.0}};
  const auto result = optimize_or_fail(machine, program, options);
  const auto written = reinterpret(machine, result.program);
  // Read back: the same moves, each part of the circle an arc with the chosen A B C.
  ASSERT_EQ(written.moves.size(), result.program.moves.size());
  for (std::size_t m = 0; m < written.moves.size(); ++m) {
    EXPECT_EQ(written.moves[m].kind, result.program.moves[m].kind);
    EXPECT_LT((written.moves[m].end_mm - result.program.moves[m].end_mm).norm(), 1e-4);
    EXPECT_LT((written.moves[m].end_abc_deg - result.program.moves[m].end_abc_deg).norm(), 1e-3);
  }
  // The read-back program's own poses move the struts as the optimum does: Σ max|ΔL| over its moves.
  const Eigen::Vector3d origin = machine.motion.program_origin_mm;
  double sum_mm = 0.0;
  ActuatorVector previous;
  for (std::size_t m = 0; m < written.moves.size(); ++m) {
    Pose pose;
    pose.position_mm = written.moves[m].end_mm + origin;
    pose.rotation =
        rotation_from_angles(AngleConvention::abc, written.moves[m].end_abc_deg * std::numbers::pi / 180.0);
    auto lengths = machine.mechanism->inverse(pose);
    ASSERT_TRUE(lengths);
    if (m > 0) sum_mm += (*lengths - previous).cwiseAbs().maxCoeff();
    previous = *lengths;
  }
  EXPECT_NEAR(sum_mm, result.greedy.metrics.increment_sum_mm, 0.05);  // A B C written to 1e-4°
  EXPECT_LT(sum_mm, result.constant.increment_sum_mm - 10.0);
}

TEST(PostProcessor, MachiningTimeDropsByTheIncrementRatio) {
  // A planar tripod whose struts are slow (5 mm/s) against the programmed feed (10 mm/s): the struts set
  // the pace everywhere, so the time follows Σ max|ΔL| (Smirnov 2019, §3.1).
  std::string text;
  {
    std::ifstream in(source_path("examples/machines/planar3.yaml"));
    std::stringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  text +=
      "limits:\n  actuator_speed: 5\n  actuator_accel: 2000\nmotion:\n  path_accel_mm_s2: 2000\n  "
      "path_jerk_mm_s3: 200000\n";
  const Machine machine = machine_from_text(text, "slow_planar3.yaml");
  const auto program = gcode_for(machine, circle_program(40.0, 0.0, 15.0));
  redundancy::OptimizeOptions options;
  options.step_mm = one_degree_mm(40.0);
  options.bounds_deg = redundancy::FreeBounds{{5.0, 30.0}};
  const auto result = optimize_or_fail(machine, program, options);
  const double predicted = result.constant.increment_sum_mm / result.greedy.metrics.increment_sum_mm;

  const auto constant_plan = plan_or_fail(machine, program);
  const auto optimized_plan = plan_or_fail(machine, reinterpret(machine, result.program));
  const test::Run constant_run = run_plan(machine, constant_plan, 100.0, false);
  const test::Run optimized_run = run_plan(machine, optimized_plan, 100.0, false);
  expect_motion_invariants(machine, optimized_plan, optimized_run, "optimized");
  const double measured = constant_run.summary.duration_s / optimized_run.summary.duration_s;
  EXPECT_NEAR(measured, predicted, 0.02 * predicted)
      << "constant " << constant_run.summary.duration_s << " s, optimized "
      << optimized_run.summary.duration_s << " s";
}

// CL data gives the tool as an axis vector; the written G-code has A B C on every move, the approach before
// the optimised points included, each meaning the CL's tool axis, and it plans on the machine.
TEST(PostProcessor, AFiveAxisClProgramIsWrittenWithAnglesThatMeanItsToolAxes) {
  for (const char* file : {"hexaglide.yaml", "hexapod_ch5.yaml"}) {
    const Machine machine = machine_from_example(std::string("examples/machines/") + file);
    const planning::ProgramStart start = planning::program_start(machine);
    program::InterpretOptions interpret;
    interpret.start_mm = start.start_mm;
    interpret.start_abc_deg = start.start_abc_deg;
    auto cl = program::load_part_program(source_path("examples/programs/ball_end_5axis.cl"), interpret);
    ASSERT_TRUE(cl.ok()) << cl.error().message;
    redundancy::OptimizeOptions options;
    options.law.law = Law::rotation;
    options.step_mm = 5.0;
    const auto result = optimize_or_fail(machine, *cl, options);
    const Eigen::Vector3d axis = machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ();
    int approach = 0;
    for (const program::CanonicalMove& move : result.program.moves) {
      ASSERT_EQ(move.orientation, program::OrientationSource::abc) << file << " line " << move.line;
    }
    // The approach: the moves before the optimised points, kept as programmed.
    for (int m = 0; m < result.points.first_move; ++m) {
      const program::CanonicalMove& original = cl->moves[m];
      const program::CanonicalMove& written = result.program.moves[m];
      ASSERT_EQ(written.line, original.line);
      const Eigen::Matrix3d rotation =
          rotation_from_angles(AngleConvention::abc, written.end_abc_deg * std::numbers::pi / 180.0);
      EXPECT_LT((rotation * axis - original.tool_axis.normalized()).norm(), 1e-9)
          << file << " line " << original.line;
      ++approach;
    }
    EXPECT_GE(approach, 1) << file;
    const auto written = reinterpret(machine, result.program);
    EXPECT_GT(plan_or_fail(machine, written).duration_s, 0.0) << file;
  }
}

}  // namespace
}  // namespace pkm::test
