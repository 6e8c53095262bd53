// Every assembly mode of the tricept: on the shipped tricept and on random tricept geometries the
// ground-truth tool point is among the modes, every mode fits the strut lengths to 1e-10 mm, and a grid four
// times denser than the default finds no more.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "machine/solution_set.hpp"
#include "machine/tricept.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Machine shipped_tricept() {
  auto machine = load_machine_file(test::source_path("examples/machines/tricept.yaml"));
  if (!machine) throw std::runtime_error(machine.error().message);
  return std::move(machine.value());
}

// examples/machines/tricept.yaml's geometry with every joint moved up to `spread_mm` at random (0: as
// shipped), homed at the shipped home tool point.
Tricept random_tricept(std::mt19937_64& rng, double spread_mm) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TriceptGeometry geometry;
  geometry.base_joints_mm = {Eigen::Vector3d(0.0, 450.0, 0.0),
                             Eigen::Vector3d(-389.7114317029974, -225.0, 0.0),
                             Eigen::Vector3d(389.7114317029974, -225.0, 0.0)};
  geometry.platform_joints_mm = {Eigen::Vector3d(0.0, 200.0, 0.0),
                                 Eigen::Vector3d(-173.20508075688772, -100.0, 0.0),
                                 Eigen::Vector3d(173.20508075688772, -100.0, 0.0)};
  geometry.tool_offset_mm = 250.0;
  auto shake = [&](Eigen::Vector3d& v) { v += spread_mm * Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (auto& a : geometry.base_joints_mm) shake(a);
  for (auto& b : geometry.platform_joints_mm) shake(b);
  shake(geometry.center_joint_mm);
  auto tricept = Tricept::create(geometry, AngleConvention::abc, Eigen::Vector3d(0.0, 0.0, 1050.0));
  if (!tricept) throw std::runtime_error(tricept.error().message);
  return std::move(tricept.value());
}

double worst_residual_mm(const Mechanism& mechanism, const ActuatorVector& q,
                         const std::vector<FkSolution>& modes) {
  double worst = 0.0;
  for (const FkSolution& s : modes) {
    auto at = mechanism.inverse(s.pose);
    if (!at) return INFINITY;
    worst = std::max(worst, (*at - q).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(TriceptAllModes, TheGroundTruthIsAmongTheModesAndADenserGridFindsNoMore) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // make sanitize sets PKM_RANDOM_GEOMETRIES (its runs are ~20× slower): fewer random tricepts there.
  const int trials = std::getenv("PKM_RANDOM_GEOMETRIES") != nullptr ? 2 : 8;
  for (int trial = 0; trial < trials; ++trial) {
    const Tricept tricept = random_tricept(rng, trial == 0 ? 0.0 : 40.0);
    const Mechanism& mechanism = tricept;
    Pose pose = mechanism.home();
    pose.position_mm += Eigen::Vector3d(80 * u(rng), 80 * u(rng), 60 * u(rng));
    auto complete = mechanism.complete_pose(pose);
    ASSERT_TRUE(complete) << complete.error().message;
    auto q = mechanism.inverse(*complete);
    ASSERT_TRUE(q) << q.error().message;
    auto modes = mechanism.assembly_modes(*q);
    ASSERT_TRUE(modes) << modes.error().message;
    EXPECT_TRUE(contains_solution(modes->solutions, *complete)) << "trial " << trial;
    EXPECT_LE(worst_residual_mm(mechanism, *q, modes->solutions), 1e-10) << "trial " << trial;
    EXPECT_EQ(modes->report.real, static_cast<int>(modes->solutions.size()));
    auto denser = tricept.assembly_modes_on_grid(*q, 4 * Tricept::kAssemblyGridDirections / 2,
                                                 2 * Tricept::kAssemblyGridRadii);
    ASSERT_TRUE(denser);
    EXPECT_EQ(denser->solutions.size(), modes->solutions.size()) << "trial " << trial;
    for (const FkSolution& s : denser->solutions) {
      EXPECT_TRUE(contains_solution(modes->solutions, s.pose)) << "trial " << trial;
    }
  }
}

TEST(TriceptAllModes, BadLengthsAreRefused) {
  const Machine machine = shipped_tricept();
  ActuatorVector q = ActuatorVector::Constant(3, 700.0);
  q[1] = std::nan("");
  auto nan = machine.mechanism->assembly_modes(q);
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.error().code, ErrorCode::bad_input);
  EXPECT_FALSE(machine.mechanism->forward_all(ActuatorVector::Constant(2, 700.0)));
  // Lengths no tool point fits: strut 1 longer than struts 2 and 3 plus the base and flange can span.
  ActuatorVector apart(3);
  apart << 3000.0, 100.0, 100.0;
  auto far = machine.mechanism->forward_all(apart);
  ASSERT_FALSE(far);
  EXPECT_EQ(far.error().code, ErrorCode::unreachable);
}

}  // namespace
}  // namespace pkm
