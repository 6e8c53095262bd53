// The interpolation along a plan made while it streams (interpolate_streamed: timing and strut laws as
// windows that follow the interpolator) against the interpolation of the whole plan: every period's steps,
// ideal values, line and contour error equal to the bit, the summaries equal, and the windows not growing
// with the program.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "interpolation/interpolate_run.hpp"
#include "planning/cam_program_generator.hpp"
#include "planning/plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm::interpolation {
namespace {

using test::CamShape;

struct RecordedRun {
  InterpolateSummary summary;
  std::vector<StepPeriod> periods;
  std::vector<PeriodContour> contours;
  std::vector<Eigen::Vector3d> path_points;
};

InterpolateOptions recording(InterpolateOptions options, RecordedRun& run) {
  options.on_period = [&run](const StepPeriod& period, const PeriodContour& contour,
                             const Eigen::Vector3d& path_mm) {
    run.periods.push_back(period);
    run.contours.push_back(contour);
    run.path_points.push_back(path_mm);
  };
  return options;
}

RecordedRun whole_run(const Machine& machine, const program::CanonicalProgram& program,
                      const InterpolateOptions& options) {
  RecordedRun run;
  const planning::MotionPlan plan = test::plan_or_fail(machine, program);
  auto timing = IdealTiming::from_plan(plan, machine);
  if (!timing) throw std::runtime_error(timing.error().message);
  auto summary = interpolate(machine, plan.path, *timing, recording(options, run), {}, program.source);
  if (!summary) throw std::runtime_error(summary.error().message);
  run.summary = *summary;
  return run;
}

RecordedRun streamed_run(const Machine& machine, const program::CanonicalProgram& program,
                         const InterpolateOptions& options) {
  RecordedRun run;
  // Two streams of the same plan: the first checks it and finds δρ_max, the second is interpolated.
  auto first = planning::start_streamed_plan(machine, program, {});
  if (!first) throw std::runtime_error(first.error().message);
  auto check = check_streamed_plan(machine, **first, options.amplification_spacing, program.source, {});
  if (!check) throw std::runtime_error(check.error().message);
  auto second = planning::start_streamed_plan(machine, program, {});
  if (!second) throw std::runtime_error(second.error().message);
  auto summary = interpolate_streamed(machine, **second, *check, recording(options, run), {}, program.source);
  if (!summary) throw std::runtime_error(summary.error().message);
  run.summary = *summary;
  return run;
}

void expect_same_summary(const InterpolateSummary& a, const InterpolateSummary& b, const std::string& label) {
  EXPECT_EQ(a.periods, b.periods) << label;
  EXPECT_EQ(a.delta_rho_max, b.delta_rho_max) << label;
  EXPECT_EQ(a.delta_rho_max_line, b.delta_rho_max_line) << label;
  EXPECT_EQ(a.ideal_time_s, b.ideal_time_s) << label;
  EXPECT_EQ(a.laws.pieces, b.laws.pieces) << label;
  EXPECT_EQ(a.laws.polynomial, b.laws.polynomial) << label;
  EXPECT_EQ(a.laws.max_fit_error, b.laws.max_fit_error) << label;
  EXPECT_EQ(a.laws.max_fit_error_line, b.laws.max_fit_error_line) << label;
  EXPECT_EQ(a.carrier.chord_reduced_periods, b.carrier.chord_reduced_periods) << label;
  EXPECT_EQ(a.carrier.max_chord_error, b.carrier.max_chord_error) << label;
  EXPECT_EQ(a.contour.max_error_mm, b.contour.max_error_mm) << label;
  EXPECT_EQ(a.contour.max_error_line, b.contour.max_error_line) << label;
  EXPECT_EQ(a.contour.end_error_mm, b.contour.end_error_mm) << label;
  EXPECT_EQ(a.corrector.fk_solves, b.corrector.fk_solves) << label;
  EXPECT_EQ(a.start_position, b.start_position) << label;
  EXPECT_EQ(a.end_position, b.end_position) << label;
  EXPECT_EQ(a.ideal_end, b.ideal_end) << label;
}

void expect_same_runs(const Machine& machine, const program::CanonicalProgram& program,
                      const InterpolateOptions& options, const std::string& label) {
  const RecordedRun whole = whole_run(machine, program, options);
  const RecordedRun streamed = streamed_run(machine, program, options);
  ASSERT_GT(whole.periods.size(), 1000u) << label;
  ASSERT_EQ(whole.periods.size(), streamed.periods.size()) << label;
  for (std::size_t k = 0; k < whole.periods.size(); ++k) {
    const StepPeriod& a = whole.periods[k];
    const StepPeriod& b = streamed.periods[k];
    ASSERT_EQ(a.index, b.index) << label << " period " << k;
    ASSERT_EQ(a.line, b.line) << label << " period " << k;
    ASSERT_EQ(a.time_s, b.time_s) << label << " period " << k;
    ASSERT_EQ(a.steps, b.steps) << label << " period " << k;
    ASSERT_EQ(a.position, b.position) << label << " period " << k;
    ASSERT_EQ(a.ideal_steps, b.ideal_steps) << label << " period " << k;
    ASSERT_EQ(whole.contours[k].max_error_mm, streamed.contours[k].max_error_mm) << label << " period " << k;
    ASSERT_TRUE(whole.path_points[k] == streamed.path_points[k]) << label << " period " << k;
  }
  expect_same_summary(whole.summary, streamed.summary, label);
  // The windows held a part of the path only.
  EXPECT_GT(streamed.summary.peak_window_pieces, 0u) << label;
  EXPECT_LT(streamed.summary.peak_window_pieces, static_cast<std::size_t>(whole.summary.laws.pieces))
      << label;
  EXPECT_LT(streamed.summary.peak_window_ticks, whole.periods.size()) << label;
}

InterpolateOptions options_for(Method method) {
  InterpolateOptions options;
  options.method = method;
  options.period_s = 0.002;
  return options;
}

TEST(StreamedInterpolation, EveryPeriodEqualsTheWholePlansOnGeneratedCamPrograms) {
  int seed = 0;
  for (const char* file : {"hexapod_ch5.yaml", "tricept.yaml", "planar3.yaml", "rotopod.yaml"}) {
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    for (CamShape shape : {CamShape::noisy_circle, CamShape::zigzag, CamShape::mixed_arcs}) {
      const std::string text = test::cam_program(machine, shape, 600, 9100 + seed++);
      const program::CanonicalProgram program = test::gcode_for(machine, text, "cam.ngc");
      expect_same_runs(machine, program, options_for(Method::carrier_corrected),
                       std::string(file) + " " + test::cam_shape_name(shape));
    }
  }
}

TEST(StreamedInterpolation, TheOtherMethodsAndOverrideChangesGiveTheWholePlansPeriods) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const std::string text = test::cam_program(machine, CamShape::mixed_arcs, 600, 9201);
  const program::CanonicalProgram program = test::gcode_for(machine, text, "cam.ngc");
  expect_same_runs(machine, program, options_for(Method::carrier), "carrier");
  expect_same_runs(machine, program, options_for(Method::exact), "exact");
  InterpolateOptions overridden = options_for(Method::carrier_corrected);
  overridden.feed_override.changes = {{0.5, 30.0}, {1.5, 150.0}, {3.0, 100.0}};
  expect_same_runs(machine, program, overridden, "override 100 → 30 → 150 → 100 %");
}

TEST(StreamedInterpolation, TheWindowsDoNotGrowWithTheProgram) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const InterpolateOptions options = options_for(Method::carrier);
  const std::string once = test::cam_program(machine, CamShape::noisy_circle, 500, 77, 2);
  const std::string ten_times = test::cam_program(machine, CamShape::noisy_circle, 500, 77, 20);
  const RecordedRun small = streamed_run(machine, test::gcode_for(machine, once, "cam.ngc"), options);
  const RecordedRun large = streamed_run(machine, test::gcode_for(machine, ten_times, "cam.ngc"), options);
  EXPECT_GT(large.summary.periods, 9 * small.summary.periods);
  EXPECT_GT(large.summary.laws.pieces, 9 * small.summary.laws.pieces);
  EXPECT_LE(large.summary.peak_window_ticks, small.summary.peak_window_ticks * 11 / 10);
  EXPECT_LE(large.summary.peak_window_pieces, small.summary.peak_window_pieces * 11 / 10);
  // The path's window is compacted once what it has forgotten is half of it: up to twice what is needed.
  EXPECT_LE(large.summary.peak_window_segments, small.summary.peak_window_segments * 2);
  EXPECT_LT(large.summary.peak_window_segments * 10, static_cast<std::size_t>(large.summary.laws.pieces));
}

TEST(StreamedInterpolation, APlanThatLeavesTheActuatorRangeIsRefusedBeforeAnyPeriod) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  // Line 4 goes far beyond the struts' reach, after a first move that is fine.
  const program::CanonicalProgram program =
      test::gcode_for(machine, "G21 G90\nG1 X10 F1000\nG1 X20\nG1 Z400\nM2\n", "far.ngc");
  auto first = planning::start_streamed_plan(machine, program, {});
  ASSERT_TRUE(first.ok()) << first.error().message;
  auto check = check_streamed_plan(machine, **first, 1.0, program.source, {});
  ASSERT_FALSE(check.ok());
  EXPECT_NE(check.error().message.find("far.ngc:4"), std::string::npos) << check.error().message;
}

}  // namespace
}  // namespace pkm::interpolation
