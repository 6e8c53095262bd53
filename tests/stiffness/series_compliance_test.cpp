// The struts with their joints and carriages (StiffnessModel::struts_joints, strut_compliance.hpp):
//  - joints: each strut's spring in series with K_u at both ends equals the strut-only model with
//    1/c_eff = 1/c + K_u,base + K_u,platform, on random hexapods and stiffness values;
//  - carriage drives of glide machines: with rigid struts and guides, the compliance is the drives' own,
//    (Jᵀ diag(k_d) J)⁻¹ with J the mechanism's twist Jacobian (carriage travel per platform twist, which
//    the glide mechanism computes independently of the series formula);
//  - guides give way only across the guide: a guide compliance adds nothing along a strut parallel to it;
//  - the strut-only model ignores what the joints and carriages give.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <random>

#include "dynamics/dynamics_test_support.hpp"
#include "stiffness/compliance_model.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm {
namespace {

TEST(SeriesCompliance, JointsAddTheirCompliancesAlongEachStrut) {
  std::mt19937_64 rng(1502);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    const Machine machine = test::random_hexapod_machine(rng, trial);
    const Mechanism& mech = *machine.mechanism;
    StiffnessParameters with_joints;
    with_joints.strut_count = mech.actuator_count();
    with_joints.line = 1;
    with_joints.model = StiffnessModel::struts_joints;
    StiffnessParameters equivalent = with_joints;
    equivalent.model = StiffnessModel::struts;
    for (int j = 0; j < with_joints.strut_count; ++j) {
      const double c = 5e4 + 3e5 * unit(rng);
      with_joints.struts[j].stiffness_N_mm = c;
      with_joints.joints[j].base_mm_N = 2e-6 * unit(rng);
      with_joints.joints[j].platform_mm_N = 2e-6 * unit(rng);
      with_joints.joints[j].rotational_rad_Nmm = 1e-9 * unit(rng);  // passes no moment: no effect
      equivalent.struts[j].stiffness_N_mm =
          1.0 / (1.0 / c + with_joints.joints[j].base_mm_N + with_joints.joints[j].platform_mm_N);
    }
    const Pose pose = *mech.complete_pose(mech.home());
    auto series = stiffness::strut_compliance(mech, with_joints, pose);
    auto direct = stiffness::strut_compliance(mech, equivalent, pose);
    ASSERT_TRUE(series.ok() && direct.ok());
    EXPECT_LT((series->compliance - direct->compliance).norm(), 1e-12 * direct->compliance.norm());
    // The joints only add compliance: C_series − C_struts is positive semi-definite.
    StiffnessParameters struts_only = with_joints;
    struts_only.model = StiffnessModel::struts;
    auto stiff = stiffness::strut_compliance(mech, struts_only, pose);
    ASSERT_TRUE(stiff.ok());
    const Eigen::SelfAdjointEigenSolver<stiffness::Matrix6> difference(series->compliance -
                                                                       stiff->compliance);
    EXPECT_GT(difference.eigenvalues().minCoeff(), -1e-12 * series->compliance.norm());
    EXPECT_GT(difference.eigenvalues().maxCoeff(), 0.0);
  }
}

// Glide machines: the carriage's drive is a spring on the actuator coordinate.
TEST(SeriesCompliance, CarriageDrivesAloneGiveTheDrivesCompliance) {
  for (const char* file : {"hexaglide.yaml", "triglide.yaml"}) {
    SCOPED_TRACE(file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *machine.mechanism;
    const int n = mech.actuator_count();
    StiffnessParameters p;
    p.strut_count = n;
    p.line = 1;
    p.model = StiffnessModel::struts_joints;
    ActuatorVector drive(n);
    for (int j = 0; j < n; ++j) {
      p.struts[j].stiffness_N_mm = 1e18;  // rigid struts
      drive[j] = 1e4 * (1.0 + 0.3 * j);
      p.carriages[j].drive_stiffness_N_mm = drive[j];
    }
    const Pose pose = *mech.complete_pose(mech.home());
    auto series = stiffness::strut_compliance(mech, p, pose);
    ASSERT_TRUE(series.ok()) << series.error().message;
    JacobianMatrix jacobian;
    ASSERT_TRUE(mech.twist_jacobian(pose, jacobian));
    const int dof = series->dof;
    if (dof == 6) {
      const stiffness::Matrix6 k = jacobian.transpose() * drive.asDiagonal() * jacobian;
      const stiffness::Matrix6 expected = k.inverse();
      EXPECT_LT((series->compliance - expected).norm(), 1e-9 * expected.norm());
    } else {
      TwistBasis allowed;
      ASSERT_TRUE(mech.controlled_twists(series->pose, allowed));
      const Eigen::MatrixXd j_allowed = jacobian * allowed;
      const Eigen::MatrixXd k = j_allowed.transpose() * drive.asDiagonal() * j_allowed;
      const Eigen::MatrixXd expected = allowed * k.inverse() * allowed.transpose();
      EXPECT_LT((series->compliance - expected).norm(), 1e-9 * expected.norm());
    }
  }
}

TEST(SeriesCompliance, AGuideGivesWayOnlyAcrossItself) {
  StiffnessParameters p;
  p.model = StiffnessModel::struts_joints;
  p.strut_count = 1;
  p.carriages[0].guide_mm_N = 3e-6;
  const Eigen::Vector3d guide(0, 0, 2.0);  // carriage travel per unit drive value (not unit)
  EXPECT_NEAR(stiffness::series_compliance_mm_N(p, 0, Eigen::Vector3d::UnitZ(), guide), 0.0, 1e-20);
  EXPECT_NEAR(stiffness::series_compliance_mm_N(p, 0, Eigen::Vector3d::UnitX(), guide), 3e-6, 1e-20);
  const Eigen::Vector3d slanted = Eigen::Vector3d(1, 0, 1).normalized();
  EXPECT_NEAR(stiffness::series_compliance_mm_N(p, 0, slanted, guide), 1.5e-6, 1e-18);
  // A base-fixed joint has no carriage: nothing is added.
  EXPECT_EQ(stiffness::series_compliance_mm_N(p, 0, slanted, Eigen::Vector3d::Zero()), 0.0);
  // The strut-only model ignores it all.
  p.model = StiffnessModel::struts;
  p.joints[0].base_mm_N = 1e-6;
  EXPECT_EQ(stiffness::series_compliance_mm_N(p, 0, Eigen::Vector3d::UnitX(), guide), 0.0);
}

TEST(SeriesCompliance, TheModelCanBeChosenAndFrameNeedsAFrame) {
  Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  machine.stiffness.model = StiffnessModel::struts_joints;
  for (int j = 0; j < machine.stiffness.strut_count; ++j) machine.stiffness.joints[j].platform_mm_N = 1e-5;
  auto full = stiffness::ComplianceModel::make(machine);
  auto simple = stiffness::ComplianceModel::make(machine, StiffnessModel::struts);
  ASSERT_TRUE(full.ok() && simple.ok());
  EXPECT_EQ(full->model(), StiffnessModel::struts_joints);
  EXPECT_EQ(simple->model(), StiffnessModel::struts);
  const Pose pose = machine.mechanism->home();
  auto a = full->at(pose);
  auto b = simple->at(pose);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_GT(a->compliance.trace(), b->compliance.trace());
  if (machine.stiffness.frame.empty()) {
    auto frame = stiffness::ComplianceModel::make(machine, StiffnessModel::frame);
    ASSERT_FALSE(frame.ok());
    EXPECT_NE(frame.error().message.find("stiffness.frame"), std::string::npos) << frame.error().message;
  }
}

}  // namespace
}  // namespace pkm
