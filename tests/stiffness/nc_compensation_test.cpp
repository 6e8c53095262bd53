// NC pre-compensation (stiffness/nc_compensation.hpp) and what a load does through a compliance
// (stiffness/tool_deflection.hpp):
//  - the struts' tensions balance the load: Σ T_j g_j = w, on random hexapods, poses and loads;
//  - a pose-independent deflection is compensated exactly after one iteration;
//  - with the strut model (pose-dependent) the residual is ≤ 1e-6 mm within five iterations, from the
//    nominal pose and from the closed form L_cmd = IK(x) − T/c, and the closed form is already within
//    second order of the deflection.
#include "stiffness/nc_compensation.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/rotation.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "stiffness/stiffness_test_support.hpp"
#include "stiffness/tool_deflection.hpp"

namespace pkm {
namespace {

statics::Wrench random_cutting_wrench(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  statics::Wrench w;
  w.force_N = 800.0 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  w.moment_Nmm = 2e4 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  return w;
}

Pose random_pose_near_home(const Mechanism& mech, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Pose pose = mech.home();
  pose.position_mm += Eigen::Vector3d(20 * unit(rng), 20 * unit(rng), 20 * unit(rng));
  pose.rotation =
      rotation_from_rotation_vector(Eigen::Vector3d(0.05 * unit(rng), 0.05 * unit(rng), 0.05 * unit(rng))) *
      pose.rotation;
  return pose;
}

TEST(ToolDeflection, StrutTensionsBalanceTheLoad) {
  std::mt19937_64 rng(1503);
  for (int trial = 0; trial < 8; ++trial) {
    const Machine machine = test::random_hexapod_machine(rng, trial);
    const Mechanism& mech = *machine.mechanism;
    const StiffnessParameters parameters =
        test::random_strut_stiffness(rng, mech.actuator_count(), 2e4, 2.2e5);
    auto compliance = stiffness::strut_compliance(mech, parameters, random_pose_near_home(mech, rng));
    ASSERT_TRUE(compliance.ok()) << compliance.error().message;
    const statics::Wrench w = random_cutting_wrench(rng);
    const stiffness::ToolDeflection d = stiffness::deflect(*compliance, w, Eigen::Vector3d::UnitZ());
    const stiffness::Vector6 balance = compliance->strut_lines.transpose() * d.strut_force_N;
    stiffness::Vector6 load;
    load << w.force_N, w.moment_Nmm;
    EXPECT_LT((balance - load).norm(), 1e-9 * load.norm()) << "trial " << trial;
    EXPECT_DOUBLE_EQ(d.normal_mm, d.displacement_mm.z());
  }
}

TEST(NcCompensation, APoseIndependentDeflectionIsCompensatedInOneIteration) {
  std::mt19937_64 rng(1504);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    stiffness::Vector6 delta;
    for (int i = 0; i < 6; ++i) delta[i] = (i < 3 ? 0.05 : 1e-4) * gauss(rng);
    Pose nominal;
    nominal.position_mm = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)) * 300.0;
    nominal.rotation = rotation_from_rotation_vector(Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
    int calls = 0;
    const stiffness::DeflectionAt constant = [&](const Pose&) -> Result<stiffness::Vector6> {
      ++calls;
      return delta;
    };
    auto compensated = stiffness::compensate_pose(nominal, constant);
    ASSERT_TRUE(compensated.ok()) << compensated.error().message;
    EXPECT_EQ(compensated->iterations, 1);
    EXPECT_LT(compensated->residual_mm, 1e-12);
    EXPECT_LT(compensated->residual_rad, 1e-14);
    EXPECT_EQ(calls, 2);  // the nominal pose's deflection, then the check of the command
    EXPECT_LT((compensated->command.position_mm - (nominal.position_mm - delta.head<3>())).norm(), 1e-12);
  }
}

TEST(NcCompensation, TheStrutModelConvergesWithinFiveIterations) {
  std::mt19937_64 rng(1505);
  for (int trial = 0; trial < 8; ++trial) {
    const Machine machine = test::random_hexapod_machine(rng, trial);
    const Mechanism& mech = *machine.mechanism;
    const StiffnessParameters parameters =
        test::random_strut_stiffness(rng, mech.actuator_count(), 2e4, 2.2e5);
    const Pose nominal = *mech.complete_pose(random_pose_near_home(mech, rng));
    const statics::Wrench w = random_cutting_wrench(rng);
    stiffness::Vector6 wrench;
    wrench << w.force_N, w.moment_Nmm;
    const stiffness::DeflectionAt deflection = [&](const Pose& command) -> Result<stiffness::Vector6> {
      auto c = stiffness::strut_compliance(mech, parameters, command);
      if (!c) return c.error();
      return stiffness::Vector6(c->compliance * wrench);
    };
    stiffness::CompensationOptions options;
    options.tolerance_mm = 1e-6;
    options.tolerance_rad = 1e-9;
    auto fixed_point = stiffness::compensate_pose(nominal, deflection, options);
    ASSERT_TRUE(fixed_point.ok()) << fixed_point.error().message;
    EXPECT_LE(fixed_point->iterations, 5);
    EXPECT_LE(fixed_point->residual_mm, 1e-6);

    // The closed form L_cmd = IK(x) − T/c leaves a second-order residual: half the load, a quarter of it.
    double residual[2] = {0.0, 0.0};
    for (int half = 0; half < 2; ++half) {
      const double scale = half ? 0.5 : 1.0;
      statics::Wrench scaled{scale * w.force_N, scale * w.moment_Nmm};
      const stiffness::Vector6 scaled_wrench = scale * wrench;
      const stiffness::DeflectionAt scaled_deflection =
          [&](const Pose& command) -> Result<stiffness::Vector6> {
        auto c = stiffness::strut_compliance(mech, parameters, command);
        if (!c) return c.error();
        return stiffness::Vector6(c->compliance * scaled_wrench);
      };
      auto at_nominal = stiffness::strut_compliance(mech, parameters, nominal);
      ASSERT_TRUE(at_nominal.ok());
      const stiffness::ToolDeflection d = stiffness::deflect(*at_nominal, scaled, Eigen::Vector3d::UnitZ());
      const ActuatorVector lengths =
          *mech.inverse(nominal) - d.strut_force_N.cwiseQuotient(at_nominal->strut_stiffness_N_mm);
      auto start = mech.forward(lengths, nominal);
      ASSERT_TRUE(start.ok());
      stiffness::CompensationOptions check_only;  // no iteration: the closed form's own residual
      check_only.max_iterations = 0;
      check_only.tolerance_mm = 1e9;
      check_only.tolerance_rad = 1e9;
      auto closed = stiffness::compensate_pose(nominal, scaled_deflection, check_only, &start->pose);
      ASSERT_TRUE(closed.ok());
      residual[half] = closed->residual_mm;
      // Far below the deflection it removes.
      EXPECT_LT(closed->residual_mm, 0.02 * d.displacement_mm.norm()) << "trial " << trial;
    }
    EXPECT_NEAR(residual[0] / residual[1], 4.0, 0.4) << "trial " << trial;
  }
}

TEST(NcCompensation, ReportsWhenItDoesNotConverge) {
  // A deflection that grows with the correction never settles.
  Pose nominal;
  const stiffness::DeflectionAt diverging = [&](const Pose& command) -> Result<stiffness::Vector6> {
    stiffness::Vector6 delta = stiffness::Vector6::Zero();
    delta.head<3>() = 2.0 * (nominal.position_mm - command.position_mm) + Eigen::Vector3d(1, 0, 0);
    return delta;
  };
  auto result = stiffness::compensate_pose(nominal, diverging);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::not_converged);
}

}  // namespace
}  // namespace pkm
