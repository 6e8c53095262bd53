// The dissertation's chapter-5 test line on its test hexapod (Smirnov 2019, §5.2.3): (−50, 0, 700) → (50, 0,
// 700) at 50 mm/s. Struts 2 and 3 reverse direction during the move, the others do not; at 1 kHz the tool
// stays within 1e-4 mm of the line (FK of the actuators, at mid-period, where the drives' straight-line
// motion between setpoints deviates most).
#include <gtest/gtest.h>

#include <cmath>

#include "plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

TEST(PlanCh5Line, StrutsTwoAndThreeReverseAndThePathErrorStaysBelowTenthMicron) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  ASSERT_NEAR(machine.motion.program_origin_mm.z(), 700.0, 1e-12) << "the example puts program Z0 at z = 700";
  const auto program =
      test::gcode_for(machine, "G21 G90 G17\nG0 X-50 Y0 Z0\nG1 X50 F3000\nM2\n", "ch5_line.ngc");
  planning::PlanOptions options;
  options.rate_hz = 1000.0;
  const auto plan = test::plan_or_fail(machine, program, options);
  const auto run = test::run_plan(machine, plan);

  // The ticks of the feed move (line 3), from rest to rest.
  std::vector<const planning::ServoTick*> line;
  for (const auto& tick : run.ticks) {
    if (tick.line == 3) line.push_back(&tick);
  }
  ASSERT_GT(line.size(), 1500u);  // 100 mm at 50 mm/s is 2 s, plus acceleration
  EXPECT_NEAR(line.back()->pose.position_mm.x(), 50.0, 1e-12);
  EXPECT_NEAR(line.back()->pose.position_mm.z(), 700.0, 1e-12);
  std::array<int, 6> reversals{};
  std::array<int, 6> direction{};
  for (std::size_t k = 1; k < line.size(); ++k) {
    for (int j = 0; j < 6; ++j) {
      const double dq = line[k]->actuators[j] - line[k - 1]->actuators[j];
      const int d = dq > 1e-9 ? 1 : dq < -1e-9 ? -1 : 0;
      if (d != 0 && direction[j] != 0 && d != direction[j]) ++reversals[j];
      if (d != 0) direction[j] = d;
    }
  }
  EXPECT_EQ(reversals[0], 0);
  EXPECT_EQ(reversals[1], 1) << "strut 2 reverses mid-move";
  EXPECT_EQ(reversals[2], 1) << "strut 3 reverses mid-move";
  EXPECT_EQ(reversals[3], 0);
  EXPECT_EQ(reversals[4], 0);
  EXPECT_EQ(reversals[5], 0);

  // Cruise at the programmed 50 mm/s, never above it.
  double top = 0.0;
  for (const auto* tick : line) top = std::max(top, tick->path_speed);
  EXPECT_NEAR(top, 50.0, 1e-6);
  EXPECT_LT(run.summary.max_path_error_mm, 1e-4);
  EXPECT_EQ(run.summary.fk_failures, 0);
  // The strut lengths at the line's start are the ones Smirnov 2019 prints (§5.2.5).
  const std::array<double, 6> e2 = {623.7911728445, 607.5487036598, 603.1222458757,
                                    586.3074649620, 588.5880863511, 621.6397151039};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(line.front()->actuators[j], e2[j], 1e-6) << j;
}

}  // namespace
}  // namespace pkm
