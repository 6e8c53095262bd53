// Properties of the three laws and both solvers, on Smirnov 2019's machines: never worse than holding, bounds
// and singular positions respected, energy at least the required work, force limits honoured, bad input
// named.
#include <gtest/gtest.h>

#include "redundancy_test_support.hpp"

namespace pkm::test {
namespace {

using redundancy::Law;

redundancy::OptimizeOptions planar_options(Law law) {
  redundancy::OptimizeOptions options;
  options.law.law = law;
  options.step_mm = one_degree_mm(40.0);
  options.bounds_deg = redundancy::FreeBounds{{5.0, 30.0}};
  auto loads = statics::parse_load_spec("tangential=1000,normal=100,cutter_radius=5,contact=right");
  EXPECT_TRUE(loads);
  options.loads = *loads;
  return options;
}

// Greedy: every step is at least as good as holding the previous values (Smirnov 2019, §3.4: "hold" is a
// candidate).
TEST(RedundancyLaws, GreedyStepsNeverLoseToHolding) {
  const Machine machine = machine_from_text(ch3_hexapod_text(30.0), "ch3_hexapod.yaml");
  const auto program = gcode_for(machine, circle_program(50.0, 700.0));
  for (Law law : {Law::increment, Law::force, Law::energy}) {
    redundancy::OptimizeOptions options;
    options.law.law = law;
    options.free = redundancy::FreeSet::all;
    options.step_mm = 3.0;
    options.bounds_deg = redundancy::FreeBounds{{-10.0, 10.0}};
    auto loads = statics::parse_load_spec("tangential=800,normal=300,axial=200");
    ASSERT_TRUE(loads);
    options.loads = *loads;
    const auto result = optimize_or_fail(machine, program, options);
    auto free = redundancy::FreeCoordinates::create(*machine.mechanism, options.free, options.bounds_deg,
                                                    result.start_rad);
    ASSERT_TRUE(free);
    redundancy::LawEvaluator evaluator(machine, *free, options.law, true);
    const auto& trajectory = result.greedy.trajectory;
    const auto& points = result.points.points;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      redundancy::Node hold;
      redundancy::Node chosen;
      statics::LoadPoint load_point;
      load_point.tangent = points[k + 1].tangent;
      load_point.line = points[k + 1].line;
      const statics::Wrench load = options.loads.wrench_at(load_point);
      ASSERT_TRUE(evaluator.evaluate(points[k + 1], load, trajectory.values[k], hold, false));
      ASSERT_TRUE(evaluator.evaluate(points[k + 1], load, trajectory.values[k + 1], chosen, false));
      EXPECT_LE(evaluator.step_cost(trajectory.nodes[k], chosen),
                evaluator.step_cost(trajectory.nodes[k], hold) + 1e-9)
          << to_string(law) << " step " << k;
    }
  }
}

// The energy law (93) on the planar circle: the whole-path solver brings the drive energy down to the work
// the cut requires (the theoretical minimum, (87)); the per-step greedy is myopic there — it keeps one drive
// from braking by turning φ until it meets the 5° bound, where every later step costs more — which is why
// pkm reports both solvers. On the hexapod with three free angles the greedy saves energy too.
TEST(RedundancyLaws, EnergyLawSavesEnergyButNotBelowTheRequiredWork) {
  const Machine machine = machine_from_example("examples/machines/planar3.yaml");
  const auto program = gcode_for(machine, circle_program(40.0, 0.0, 15.0));
  auto options = planar_options(Law::energy);
  options.solver = redundancy::Solver::global;
  const auto result = optimize_or_fail(machine, program, options);
  const auto& constant = result.constant;
  ASSERT_TRUE(result.whole_path.has_value());
  const auto& whole = result.whole_path->metrics;
  EXPECT_GT(constant.energy_J, constant.required_work_J * 1.02);
  EXPECT_LT(whole.energy_J, constant.energy_J);
  EXPECT_GE(whole.energy_J, whole.required_work_J - 1e-9);
  EXPECT_LT(whole.energy_J, whole.required_work_J * 1.01);
  EXPECT_LE(whole.energy_J, result.greedy.metrics.energy_J + 1e-9);
  // With recovery, the drives' net energy is the work of the load, whatever φ does ((84)–(85)).
  auto recovery = options;
  recovery.law.energy = redundancy::EnergyAccounting::recovery;
  recovery.solver = redundancy::Solver::greedy;
  const auto regenerative = optimize_or_fail(machine, program, recovery);
  EXPECT_NEAR(regenerative.constant.energy_J, regenerative.constant.required_work_J, 1e-9);

  const Machine hexapod = machine_from_example("examples/machines/hexapod_ch3.yaml");
  const auto circle = gcode_for(hexapod, circle_program(50.0, 700.0));
  redundancy::OptimizeOptions spatial;
  spatial.law.law = Law::energy;
  spatial.free = redundancy::FreeSet::all;
  spatial.step_mm = 2.0;
  spatial.bounds_deg = redundancy::FreeBounds{{-10.0, 10.0}};
  spatial.loads = *statics::parse_load_spec("tangential=1000");
  const auto three = optimize_or_fail(hexapod, circle, spatial);
  EXPECT_LT(three.greedy.metrics.energy_J, three.constant.energy_J);
  EXPECT_GE(three.greedy.metrics.energy_J, three.greedy.metrics.required_work_J - 1e-9);
}

TEST(RedundancyLaws, ForceLimitIsHonouredOrNamed) {
  const Machine machine = machine_from_example("examples/machines/planar3.yaml");
  const auto program = gcode_for(machine, circle_program(40.0, 0.0, 15.0));
  auto options = planar_options(Law::increment);
  options.law.force_limit_N = 1000.0;
  const auto result = optimize_or_fail(machine, program, options);
  EXPECT_LE(result.greedy.metrics.peak_force_N, 1000.0);
  options.law.force_limit_N = 500.0;  // below what any φ in 5…30° can do (§3.4.2: optimum ≈ 790 N)
  auto refused = redundancy::optimize_program(program, machine, options);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("test.ngc:"), std::string::npos) << refused.error().message;
}

// Smirnov 2019, §3.3: φ = 0 is singular for the uniform planar tripod at every (x, y); a law must not cross
// it even when the bounds would allow.
TEST(RedundancyLaws, LawsStayOnTheStartSideOfASingularPosition) {
  const Machine machine = machine_from_example("examples/machines/planar3.yaml");
  const auto program = gcode_for(machine, circle_program(40.0, 0.0, 15.0));
  for (Law law : {Law::increment, Law::force, Law::energy}) {
    auto options = planar_options(law);
    options.bounds_deg = redundancy::FreeBounds{{-30.0, 30.0}};
    options.solver = redundancy::Solver::global;
    const auto result = optimize_or_fail(machine, program, options);
    auto free = redundancy::FreeCoordinates::create(*machine.mechanism, options.free, options.bounds_deg,
                                                    result.start_rad);
    ASSERT_TRUE(free);
    redundancy::LawEvaluator evaluator(machine, *free, options.law, false);
    const double start_measure =
        evaluator.normalized_determinant(free->pose(result.points.points[0], result.start_rad));
    for (const auto* trajectory : {&result.greedy.trajectory, &result.whole_path->trajectory}) {
      for (std::size_t k = 0; k < trajectory->values.size(); ++k) {
        const double measure =
            evaluator.normalized_determinant(free->pose(result.points.points[k], trajectory->values[k]));
        EXPECT_GE(measure, options.law.singularity_margin * start_measure)
            << to_string(law) << " point " << k;
        EXPECT_GT(trajectory->values[k][0], 0.0);
      }
    }
  }
}

TEST(RedundancyLaws, RateLimitKeepsTheWholePathSmooth) {
  const Machine machine = machine_from_example("examples/machines/planar3.yaml");
  const auto program = gcode_for(machine, circle_program(40.0, 0.0, 15.0));
  auto options = planar_options(Law::force);
  options.solver = redundancy::Solver::global;
  options.whole_path.max_rate_deg_per_mm = 0.5;
  const auto result = optimize_or_fail(machine, program, options);
  const auto& values = result.whole_path->trajectory.values;
  const auto& points = result.points.points;
  for (std::size_t k = 1; k < values.size(); ++k) {
    EXPECT_LE(std::abs(values[k][0] - values[k - 1][0]) * 180.0 / std::numbers::pi,
              0.5 * points[k].step_mm + 1e-9);
  }
  // Smoothness costs something against the unlimited pointwise optimum, never gains.
  EXPECT_GE(result.whole_path->metrics.peak_force_N, result.greedy.metrics.peak_force_N - 1e-6);
}

TEST(RedundancyLaws, BadProgramsAreNamed) {
  const Machine machine = machine_from_example("examples/machines/hexapod_ch3.yaml");
  redundancy::OptimizeOptions options;
  struct Case {
    std::string program;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {"G0 X10 Y0 Z700\nM2\n", "no feed move"},
           {"G1 X10 Y0 Z700 F100\nG43 H1\nG1 X20 F100\nM2\n", "test.ngc:3"},
       }) {
    program::InterpretOptions interpret;
    interpret.start_mm = {0, 0, 700};
    interpret.tool_table_path = source_path("tests/program/conformance/tools.tbl");
    auto parsed = program::interpret_gcode(c.program, "test.ngc", interpret);
    ASSERT_TRUE(parsed) << parsed.error().message;
    auto result = redundancy::optimize_program(*parsed, machine, options);
    ASSERT_FALSE(result) << c.program;
    EXPECT_NE(result.error().message.find(c.message), std::string::npos) << result.error().message;
  }
}

}  // namespace
}  // namespace pkm::test
