// The strut-only tool compliance (src/stiffness/strut_compliance.hpp) against what it must equal:
//  - on random hexapods, the ch5 and ch3 hexapods, the planar machines and the tripod (whose actuators are
//    the strut lengths), a wrench w shortens each strut by P_j/c_j with P from statics (src/statics,
//    independent of the compliance), and forward kinematics of those lengths moves the platform by C w to
//    1e-4 relative (a finite-difference check, at c·L/|P| ≥ 1e4; central, w and −w);
//  - C is symmetric positive semi-definite with the mechanism's degrees of freedom as its rank;
//  - E·A/L: the stiffness follows the strut's length, and doubling E halves C;
//  - a singular position reports unbounded compliance instead of a huge number.
#include "stiffness/strut_compliance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "core/rotation.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "statics/actuator_forces.hpp"
#include "stiffness/stiffness_test_support.hpp"

namespace pkm {
namespace {

struct ComplianceCase {
  std::string label;
  Machine machine;
};

std::vector<ComplianceCase> compliance_cases() {
  std::vector<ComplianceCase> cases;
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_ch3.yaml", "planar2.yaml", "planar3.yaml", "tripod.yaml"})
    cases.push_back({file, test::machine_from_example(std::string("examples/machines/") + file)});
  std::mt19937_64 rng(515);
  for (int i = 0; i < 5; ++i)
    cases.push_back({fmt::format("random hexapod {}", i), test::random_hexapod_machine(rng, i)});
  return cases;
}

/// Random strut stiffness 50…400 N/µm.
StiffnessParameters random_strut_stiffness(std::mt19937_64& rng, int struts) {
  return test::random_strut_stiffness(rng, struts, 5e4, 4e5);
}

TEST(StrutCompliance, ForwardKinematicsOfTheShortenedStrutsMovesThePlatformByCw) {
  std::mt19937_64 rng(516);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const ComplianceCase& c : compliance_cases()) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    const Pose pose = *mech.complete_pose(mech.home());
    const StiffnessParameters parameters = random_strut_stiffness(rng, mech.actuator_count());
    auto compliance = stiffness::strut_compliance(mech, parameters, pose);
    ASSERT_TRUE(compliance.ok()) << compliance.error().message;
    // The actuators must be the struts' lengths for this check.
    ActuatorVector lengths(mech.actuator_count());
    ASSERT_TRUE(mech.actuator_values(pose, lengths.data()));
    ASSERT_LT((lengths - compliance->strut_length_mm).cwiseAbs().maxCoeff(), 1e-9);
    for (int trial = 0; trial < 3; ++trial) {
      statics::Wrench w{Eigen::Vector3d(100 * unit(rng), 100 * unit(rng), 100 * unit(rng)),
                        Eigen::Vector3d(1e4 * unit(rng), 1e4 * unit(rng), 1e4 * unit(rng))};
      auto forces = statics::actuator_forces(mech, pose, w);
      ASSERT_TRUE(forces.ok()) << forces.error().message;
      // The regime the check holds in: every strut shortened by less than 10⁻⁴ of its length.
      for (int j = 0; j < forces->size(); ++j) {
        ASSERT_GE(compliance->strut_stiffness_N_mm[j] * lengths[j] / std::abs((*forces)[j]), 1e4);
      }
      // A strut pushing the platform (P > 0) is compressed: shorter by P/c. The load and its opposite, so
      // that the central difference leaves no second-order term of the forward kinematics.
      const ActuatorVector shortening =
          forces->cwiseQuotient(compliance->strut_stiffness_N_mm.head(lengths.size()));
      auto pushed = mech.forward(lengths - shortening, pose);
      auto pulled = mech.forward(lengths + shortening, pose);
      ASSERT_TRUE(pushed.ok() && pulled.ok());
      Eigen::Matrix<double, 6, 1> measured, wrench;
      measured << 0.5 * (pushed->pose.position_mm - pulled->pose.position_mm),
          0.5 * rotation_vector_from_rotation(pushed->pose.rotation * pulled->pose.rotation.transpose());
      wrench << w.force_N, w.moment_Nmm;
      // Only what the mechanism lets the load do: the components its constraints carry do no work.
      const Eigen::Matrix<double, 6, 1> predicted = compliance->compliance * wrench;
      const double scale = std::max(predicted.head<3>().norm(), 1e-12);
      EXPECT_LT((measured.head<3>() - predicted.head<3>()).norm(), 1e-4 * scale)
          << "FK " << measured.transpose() << "\nCw " << predicted.transpose();
      EXPECT_LT((measured.tail<3>() - predicted.tail<3>()).norm(),
                1e-4 * std::max(predicted.tail<3>().norm(), scale / mech.platform_size_mm()));
    }
  }
}

TEST(StrutCompliance, IsSymmetricPositiveSemiDefiniteWithTheMechanismsDegreesOfFreedom) {
  std::mt19937_64 rng(517);
  for (const ComplianceCase& c : compliance_cases()) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    auto compliance =
        stiffness::strut_compliance(mech, random_strut_stiffness(rng, mech.actuator_count()), mech.home());
    ASSERT_TRUE(compliance.ok()) << compliance.error().message;
    const stiffness::Matrix6& m = compliance->compliance;
    EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-15 * m.cwiseAbs().maxCoeff());
    // In consistent units (rotations times the platform's size) the eigenvalues are comparable.
    Eigen::Matrix<double, 6, 1> unit_scale;
    unit_scale << 1, 1, 1, mech.platform_size_mm(), mech.platform_size_mm(), mech.platform_size_mm();
    const stiffness::Matrix6 scaled = unit_scale.asDiagonal() * m * unit_scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<stiffness::Matrix6> spectrum(scaled);
    const auto values = spectrum.eigenvalues();
    EXPECT_GT(values.minCoeff(), -1e-12 * values.maxCoeff());
    int rank = 0;
    for (int i = 0; i < 6; ++i) rank += values[i] > 1e-9 * values.maxCoeff() ? 1 : 0;
    EXPECT_EQ(rank, compliance->dof);
    EXPECT_EQ(compliance->dof, mech.controlled_axes().count());
  }
}

TEST(StrutCompliance, ModulusAndAreaGiveTheLengthsStiffnessAndScaleTheCompliance) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *machine.mechanism;
  StiffnessParameters steel;
  steel.strut_count = 6;
  steel.line = 1;
  for (int j = 0; j < 6; ++j) steel.struts[j] = StrutStiffness{0.0, 210000.0, 800.0};
  auto soft = stiffness::strut_compliance(mech, steel, mech.home());
  ASSERT_TRUE(soft.ok()) << soft.error().message;
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(soft->strut_stiffness_N_mm[j], 210000.0 * 800.0 / soft->strut_length_mm[j], 1e-9);
  }
  for (int j = 0; j < 6; ++j) steel.struts[j].modulus_N_mm2 *= 2.0;
  auto stiff = stiffness::strut_compliance(mech, steel, mech.home());
  ASSERT_TRUE(stiff.ok());
  EXPECT_LE((2.0 * stiff->compliance - soft->compliance).cwiseAbs().maxCoeff(),
            1e-12 * soft->compliance.cwiseAbs().maxCoeff());
}

TEST(StrutCompliance, ASingularPositionHasUnboundedCompliance) {
  // The ch5 hexapod turned by 90° about the vertical: Fichter's singularity of a symmetric hexapod, where
  // every strut is perpendicular to the platform's radius and nothing resists a turn about z.
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *machine.mechanism;
  auto stiffness_of_ch5 = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(stiffness_of_ch5.ok());
  auto compliance = stiffness::strut_compliance(mech, *stiffness_of_ch5, test::abc_pose(0, 0, 700, 0, 0, 90));
  ASSERT_FALSE(compliance.ok());
  EXPECT_EQ(compliance.error().code, ErrorCode::singular);
  EXPECT_NE(compliance.error().message.find("unbounded compliance"), std::string::npos)
      << compliance.error().message;
  // A few degrees away it is finite, and the weakest turn is about z.
  auto near = stiffness::strut_compliance(mech, *stiffness_of_ch5, test::abc_pose(0, 0, 700, 0, 0, 80));
  ASSERT_TRUE(near.ok()) << near.error().message;
  const auto turning = stiffness::principal_stiffness(*near, true);
  EXPECT_GT(std::abs(turning.directions.col(0).z()), 0.99);
}

TEST(StrutCompliance, TheStiffnessComesFromTheStiffnessSectionOrTheDynamicsSprings) {
  const Machine ch5 = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto from_dynamics = stiffness::strut_stiffness_of(ch5);
  ASSERT_TRUE(from_dynamics.ok()) << from_dynamics.error().message;
  EXPECT_DOUBLE_EQ(from_dynamics->struts[3].at_length(600.0), ch5.dynamics.struts[3].stiffness_N_mm);
  const Machine bare = test::machine_from_example("examples/machines/hexapod_genhexkins.yaml");
  auto none = stiffness::strut_stiffness_of(bare);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("stiffness.struts: not given"), std::string::npos);
  EXPECT_EQ(none.error().location.key, "stiffness.struts");
}

/// The ch3 hexapod (examples/machines/hexapod_ch3_delta30.yaml) with its platform joint pairs separated by
/// `separation_deg` (each joint moved half of it towards its own base joint, from the merged points at 30°,
/// 150° and 270° on the 300 mm circle).
Machine ch3_hexapod_with_separation(double separation_deg) {
  std::string text = "name: ch3\ntype: hexapod\nangles: krylov\nbase_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double a = kPi / 3 * j;
    text += fmt::format("  - [{:.12f}, {:.12f}, 0]\n", 500 * std::cos(a), 500 * std::sin(a));
  }
  text += "platform_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double merged = kPi / 6 + 2 * kPi / 3 * (j / 2);
    const double a = merged + (j % 2 == 0 ? -0.5 : 0.5) * separation_deg * kPi / 180;
    text += fmt::format("  - [{:.12f}, {:.12f}, 0]\n", 300 * std::cos(a), 300 * std::sin(a));
  }
  text += "tool: [0, 0, 200]\nhome: [0, 0, 700, 0, 0, 0]\nstiffness:\n  struts: {stiffness_N_mm: 100000}\n";
  return test::machine_from_text(text, fmt::format("ch3_separation_{}.yaml", separation_deg));
}

// The hexapod of Smirnov 2019, §3.5.1 (Table 2's layouts): on the ch3 hexapod at z = 700 mm with 10⁵ N/mm
// struts, the largest translational compliance rises monotonically as the paired platform joints separate
// from 0° to 50°.
TEST(StrutCompliance, SeparatingThePairedPlatformJointsRaisesTheLargestCompliance) {
  double previous = 0.0;
  for (double separation : {0.0, 10.0, 20.0, 30.0, 40.0, 50.0}) {
    SCOPED_TRACE(fmt::format("{}°", separation));
    const Machine machine = ch3_hexapod_with_separation(separation);
    auto compliance =
        stiffness::strut_compliance(*machine.mechanism, machine.stiffness, machine.mechanism->home());
    ASSERT_TRUE(compliance.ok()) << compliance.error().message;
    const double largest = 1.0 / stiffness::principal_stiffness(*compliance, false).stiffness[0];
    EXPECT_GT(largest, previous);
    previous = largest;
  }
}

}  // namespace
}  // namespace pkm
