// Every shipped example program plans on the ch5 hexapod within every limit, at two servo rates.
#include <gtest/gtest.h>

#include "plan_test_support.hpp"
#include "source_paths.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

class PlanExamples : public testing::TestWithParam<const char*> {};

TEST_P(PlanExamples, PlansWithinEveryLimit) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions options;
  options.start_mm = start.start_mm;
  options.start_abc_deg = start.start_abc_deg;
  auto program =
      program::load_part_program(test::source_path("examples/programs/" + std::string(GetParam())), options);
  ASSERT_TRUE(program.ok()) << program.error().message;
  for (double rate : {500.0, 2000.0}) {
    planning::PlanOptions plan_options;
    plan_options.rate_hz = rate;
    const auto plan = test::plan_or_fail(machine, *program, plan_options);
    const auto run = test::run_plan(machine, plan);
    test::expect_motion_invariants(machine, plan, run, GetParam());
    EXPECT_LT(run.summary.max_path_error_mm, 1e-3) << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, PlanExamples,
                         testing::Values("pocket.ngc", "circle.ngc", "helix.ngc", "ch5_line.ngc",
                                         "bolt_circle.ngc", "ball_end_5axis.cl"));

}  // namespace
}  // namespace pkm
