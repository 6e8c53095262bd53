// The carrier-frequency method on the chapter-5 test line of Smirnov 2019 (§5.2.3, §5.2.5): continuous
// drives at constant speed, then whole steps of 1 µm with the naive remainder registers and with the
// discreteness correction.
#include <gtest/gtest.h>

#include "interpolation_test_support.hpp"

namespace pkm {
namespace {

using interpolation::IdealTiming;
using interpolation::InterpolateOptions;
using interpolation::Method;

struct Ch5Line {
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  planning::MotionPlan plan = test::ch5_line_plan(machine, 0.005);
  IdealTiming timing = IdealTiming::constant_speed(plan.path.length(), 50.0);
};

InterpolateOptions continuous(double period_s) {
  InterpolateOptions options;
  options.method = Method::exact;
  options.period_s = period_s;
  options.step_mm = 0.0;
  options.chord_check = false;
  return options;
}

// §5.2.3: continuous drives, no acceleration; the drives' chords leave the line by at most 1.34e-5, 5.36e-5
// and 2.14e-4 mm at mid-period for h = 5, 10, 20 ms (an independent simulation; quadratic in h).
TEST(CarrierCh5Line, E13MidPeriodErrorOfContinuousDrives) {
  const Ch5Line line;
  ASSERT_NEAR(line.plan.path.length(), 100.0, 1e-9);
  const std::array<std::pair<double, double>, 3> cases = {
      {{0.005, 1.34e-5}, {0.010, 5.36e-5}, {0.020, 2.14e-4}}};
  for (const auto& [h, expected] : cases) {
    const auto exact = test::interpolate_or_fail(line.machine, line.plan.path, line.timing, continuous(h));
    EXPECT_NEAR(exact.contour.max_error_mm, expected, 0.03 * expected) << "h = " << h;
    EXPECT_LT(exact.contour.max_period_end_error_mm, 1e-9) << "period ends lie on the line";
    EXPECT_EQ(exact.periods, std::lround(2.0 / h));
    // The fitted strut laws (sqrt-quadratic on a line) give the same motion.
    InterpolateOptions fitted = continuous(h);
    fitted.method = Method::carrier;
    const auto carrier = test::interpolate_or_fail(line.machine, line.plan.path, line.timing, fitted);
    EXPECT_NEAR(carrier.contour.max_error_mm, exact.contour.max_error_mm, 1e-7);
    EXPECT_EQ(carrier.laws.sqrt_quadratic, carrier.laws.pieces);
  }
}

// §5.2.5: whole steps of 1 µm with the remainder registers; the start positions are truncated, their error
// 4.9166e-4 mm is never taken out, and the tool strays about 2e-3 mm from the line, above ρ_max = 1e-3 mm.
TEST(CarrierCh5Line, E14NaiveRemainderRegistersExceedTheTolerance) {
  const Ch5Line line;
  InterpolateOptions options;
  options.method = Method::carrier;
  options.period_s = 0.005;
  options.step_mm = 0.001;
  const auto naive = test::interpolate_or_fail(line.machine, line.plan.path, line.timing, options);
  const std::array<double, 6> e2 = {623.7911728445, 607.5487036598, 603.1222458757,
                                    586.3074649620, 588.5880863511, 621.6397151039};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(naive.ideal_start[j], e2[j], 1e-9) << "E2, strut " << j + 1;
  EXPECT_NEAR(naive.contour.start_error_mm, 4.9166e-4, 2e-8);
  EXPECT_GT(naive.contour.max_error_mm, 1e-3);
  EXPECT_LT(naive.contour.max_error_mm, 3e-3);
  EXPECT_GT(naive.contour.max_error_after_first_mm, naive.contour.start_error_mm) << "the start error stays";
  EXPECT_LT(naive.max_remainder_steps, 1.0);
  const std::array<std::int64_t, 6> e3 = {623791, 607548, 603122, 586307, 588588, 621639};
  for (int j = 0; j < 6; ++j)
    EXPECT_EQ(naive.start_position[j], e3[j]) << "E3's truncated start, strut " << j + 1;
}

// §5.2.5: the floor/ceil choice per period removes the start error in the first period and keeps the tool
// about an order of magnitude nearer the line than the naive registers.
TEST(CarrierCh5Line, E15CorrectionRemovesTheStartErrorAndCutsTheContourError) {
  const Ch5Line line;
  for (double h : {0.005, 0.010, 0.020}) {
    InterpolateOptions options;
    options.period_s = h;
    options.step_mm = 0.001;
    options.method = Method::carrier;
    const auto naive = test::interpolate_or_fail(line.machine, line.plan.path, line.timing, options);
    options.method = Method::carrier_corrected;
    const auto corrected = test::interpolate_or_fail(line.machine, line.plan.path, line.timing, options);
    EXPECT_NEAR(corrected.contour.start_error_mm, 4.9166e-4, 2e-8);
    EXPECT_LE(corrected.contour.max_error_after_first_mm, corrected.contour.start_error_mm) << "h = " << h;
    EXPECT_LT(corrected.contour.max_period_end_error_mm, 3e-4) << "period ends after the first: ≈ 1.9–2.4e-4";
    EXPECT_LT(5.0 * corrected.contour.max_error_after_first_mm, naive.contour.max_error_mm) << "h = " << h;
    EXPECT_NEAR(corrected.fk_solves_per_period, 1.0, 1e-12) << "linearised at the end: one FK solve";
  }
}

// The linearised choice (1 FK solve per period) against FK of all 64 combinations at both instants; at
// h = 10 ms the period's motion (0.5 mm) is the largest the midpoint approximation meets in the tests.
TEST(CarrierCh5Line, LinearisedChoiceMatchesTheFullForwardKinematics) {
  const Ch5Line line;
  const IdealTiming short_timing = IdealTiming::constant_speed(line.plan.path.length(), 50.0);
  InterpolateOptions options;
  options.method = Method::carrier_corrected;
  options.period_s = 0.01;
  options.step_mm = 0.001;
  const auto linear = test::interpolate_or_fail(line.machine, line.plan.path, short_timing, options);
  options.linearise = false;
  const auto full = test::interpolate_or_fail(line.machine, line.plan.path, short_timing, options);
  EXPECT_NEAR(full.fk_solves_per_period, 128.0, 1e-9);
  // The linearised errors are first-order estimates: the choices agree but for near ties.
  EXPECT_NEAR(linear.contour.max_error_after_first_mm, full.contour.max_error_after_first_mm,
              0.15 * full.contour.max_error_after_first_mm);
  EXPECT_NEAR(linear.contour.rms_error_mm, full.contour.rms_error_mm, 0.1 * full.contour.rms_error_mm);
}

}  // namespace
}  // namespace pkm
