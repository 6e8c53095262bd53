// The two inverse-kinematics scenarios of Rusanov et al.'s glide machines as laws for the free spin about the
// tool axis, on the hexaglide along generated five-axis programs: "rotation" (the simple-matrix scenario)
// turns the platform by no more than the tool axis needs, "potential" (the virtual-potential scenario) keeps
// the carriages further from the ends of their guides than the other choices.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "redundancy_test_support.hpp"

namespace pkm::test {
namespace {

using redundancy::Law;

/// A five-axis program of `moves` random G1 moves round program zero, tilting about A and B (C stays 0: the
/// spin about the tool axis is the law's to choose).
std::string tilting_program(std::uint64_t seed, int moves, double reach_mm, double tilt_deg) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> place(-reach_mm, reach_mm);
  std::uniform_real_distribution<double> tilt(-tilt_deg, tilt_deg);
  std::string text = "G21 G90 G17 G94\nG0 X0 Y0 Z0 A0 B0 C0\n";
  for (int k = 0; k < moves; ++k) {
    text += fmt::format("G1 X{:.3f} Y{:.3f} Z{:.3f} A{:.3f} B{:.3f} F1200\n", place(rng), place(rng),
                        0.2 * place(rng), tilt(rng), tilt(rng));
  }
  return text + "M2\n";
}

std::string hexaglide_text() {
  std::ifstream file(source_path("examples/machines/hexaglide.yaml"));
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

redundancy::OptimizeOptions scenario_options(Law law) {
  redundancy::OptimizeOptions options;
  options.law.law = law;
  options.solver = redundancy::Solver::global;
  options.step_mm = 2.0;
  options.bounds_deg = redundancy::FreeBounds{{-40.0, 40.0}};
  return options;
}

/// The angle (deg) between the tool axes of two nodes: any platform rotation from one to the other turns the
/// tool axis by this much, so it is at least this.
double tool_axis_turn_deg(const redundancy::Node& a, const redundancy::Node& b, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d na = a.pose.rotation * axis;
  const Eigen::Vector3d nb = b.pose.rotation * axis;
  return std::atan2(na.cross(nb).norm(), na.dot(nb)) * 180.0 / std::numbers::pi;
}

TEST(GlideScenarios, TheRotationLawTurnsThePlatformAsLittleAsTheToolAxisNeeds) {
  const Machine machine = machine_from_example("examples/machines/hexaglide.yaml");
  const Eigen::Vector3d axis = machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const auto program = gcode_for(machine, tilting_program(seed, 12, 30.0, 8.0));
    const auto rotation = optimize_or_fail(machine, program, scenario_options(Law::rotation));
    const auto increment = optimize_or_fail(machine, program, scenario_options(Law::increment));
    const auto& nodes = rotation.chosen().trajectory.nodes;
    double least_deg = 0.0;
    for (std::size_t k = 1; k < nodes.size(); ++k)
      least_deg += tool_axis_turn_deg(nodes[k - 1], nodes[k], axis);
    const double turned_deg = rotation.chosen().metrics.rotation_sum_deg;
    const std::string label = fmt::format("seed {}", seed);
    // Never less than the tool axis turns; no more than a holding spin or the increment law's choice turn it.
    EXPECT_GE(turned_deg, least_deg - 1e-9) << label;
    EXPECT_LE(turned_deg, rotation.constant.rotation_sum_deg + 1e-9) << label;
    EXPECT_LE(turned_deg, increment.chosen().metrics.rotation_sum_deg + 1e-9) << label;
    // And the minimal rotation it is: the whole-path solver refines the spin to it.
    EXPECT_LE(turned_deg, 1.001 * least_deg + 1e-3)
        << label << ": " << turned_deg << " against " << least_deg;
  }
}

TEST(GlideScenarios, ThePotentialLawKeepsTheCarriagesFurtherFromTheEndsOfTheirGuides) {
  // The hexaglide with carriage travel narrowed to what the programs need, so that the limits matter.
  std::string text = hexaglide_text();
  const std::string wide = "actuator_min: -1000, actuator_max: 1000";
  ASSERT_NE(text.find(wide), std::string::npos);
  const Machine reference = machine_from_example("examples/machines/hexaglide.yaml");
  for (std::uint64_t seed : {21u, 22u, 23u}) {
    const auto program = gcode_for(reference, tilting_program(seed, 10, 40.0, 10.0));
    const auto wide_run = optimize_or_fail(reference, program, scenario_options(Law::increment));
    // The range the holding spin uses, with 30 mm to spare at each end.
    double low = 1e9, high = -1e9;
    for (const auto& node : wide_run.chosen().trajectory.nodes) {
      low = std::min(low, node.lengths.minCoeff());
      high = std::max(high, node.lengths.maxCoeff());
    }
    std::string narrowed = text;
    narrowed.replace(narrowed.find(wide), wide.size(),
                     fmt::format("actuator_min: {:.3f}, actuator_max: {:.3f}", low - 30.0, high + 30.0));
    const Machine machine = machine_from_text(narrowed, "hexaglide_narrow.yaml");
    const auto potential = optimize_or_fail(machine, program, scenario_options(Law::potential));
    const auto increment = optimize_or_fail(machine, program, scenario_options(Law::increment));
    const std::string label = fmt::format("seed {}", seed);
    const double margin = potential.chosen().metrics.min_limit_margin;
    ASSERT_TRUE(std::isfinite(margin)) << label;
    EXPECT_GT(margin, 0.0) << label;
    EXPECT_GE(margin, potential.constant.min_limit_margin - 1e-12) << label;
    EXPECT_GE(margin, increment.chosen().metrics.min_limit_margin - 1e-12) << label;
  }
}

TEST(GlideScenarios, ThePotentialLawNeedsBothActuatorLimits) {
  std::string text = hexaglide_text();
  const std::string limits = "actuator_min: -1000, actuator_max: 1000, ";
  ASSERT_NE(text.find(limits), std::string::npos);
  text.erase(text.find(limits), limits.size());
  const Machine machine = machine_from_text(text, "hexaglide_open.yaml");
  const auto program = gcode_for(machine, tilting_program(31, 4, 20.0, 5.0));
  auto result = redundancy::optimize_program(program, machine, scenario_options(Law::potential));
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("limits.actuator_min and limits.actuator_max"), std::string::npos)
      << result.error().message;
}

}  // namespace
}  // namespace pkm::test
