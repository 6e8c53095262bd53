// The elastic model's pieces:
//  - rigid_terms (the matrix form on the right-hand side) equals equations_of_motion (the body-by-body
//    virtual powers) on random hexapods and every shipped mechanism with a free platform, carriages included;
//  - the strut force's direction: a strut stretched by δ (drive held short) pulls the platform joint towards
//    its base joint, F = c·δ, and the friction force opposes the elongation rate with the model's law;
//  - a machine that cannot have the model says why, naming the file and key.
#include "dynamics/elastic_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/wide_kernels.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "io/machine_file.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateVector;
using Vector6 = Eigen::Matrix<double, 6, 1>;

TEST(ElasticModel, RigidTermsEqualTheEquationsOfMotion) {
  std::vector<std::pair<std::string, Machine>> machines;
  std::mt19937_64 rng(101);
  for (int i = 0; i < 5; ++i)
    machines.emplace_back(fmt::format("random hexapod {}", i), test::random_hexapod_machine(rng, i));
  for (const char* file : {"hexapod_ch5.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml",
                           "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    machines.emplace_back(file, test::machine_from_example(std::string("examples/machines/") + file));
  }
  for (const auto& [label, machine] : machines) {
    SCOPED_TRACE(label);
    const Mechanism& mech = *machine.mechanism;
    TwistBasis basis;
    if (!dynamics::platform_twist_basis(mech, basis)) {
      EXPECT_EQ(label, "triglide.yaml");  // three DOF in space: no fixed basis, no elastic model
      continue;
    }
    for (int trial = 0; trial < 3; ++trial) {
      const DynamicsParameters p = test::random_dynamics_parameters(rng, mech.actuator_count());
      PoseVector c = vector_from_pose(mech.convention(), mech.home());
      const AxisMask mask = mech.controlled_axes();
      for (int axis = 0; axis < 6; ++axis) {
        if (mask.controlled[axis])
          c[axis] += axis < 3 ? test::uniform(rng, -10, 10) : test::uniform(rng, -0.05, 0.05);
      }
      const Pose pose = *mech.complete_pose(pose_from_vector(mech.convention(), c));
      CoordinateVector rates(basis.cols());
      for (int k = 0; k < basis.cols(); ++k)
        rates[k] = basis.col(k).tail<3>().squaredNorm() > 0 ? test::uniform(rng, -0.5, 0.5)
                                                            : test::uniform(rng, -80, 80);
      const Vector6 twist = basis * rates;
      const statics::Wrench load{Eigen::Vector3d(100, -50, 80), Eigen::Vector3d(2e3, 1e3, -3e3)};
      auto expected = dynamics::equations_of_motion(mech, p, pose, basis, twist, load);
      ASSERT_TRUE(expected.ok()) << expected.error().message;
      dynamics::RigidTerms terms;
      dynamics::rigid_terms(expected->state, p, basis, twist, load, terms);
      const double mass_scale = expected->mass.cwiseAbs().maxCoeff();
      EXPECT_LE((terms.mass - expected->mass).cwiseAbs().maxCoeff(), 1e-12 * mass_scale);
      EXPECT_LE((terms.bias - expected->bias).cwiseAbs().maxCoeff(),
                1e-10 * expected->bias.cwiseAbs().maxCoeff() + 1e-12 * mass_scale)
          << "matrix form " << terms.bias.transpose() << "\nvirtual powers " << expected->bias.transpose();
      EXPECT_LE((terms.applied - expected->applied).cwiseAbs().maxCoeff(),
                1e-12 * expected->applied.cwiseAbs().maxCoeff());
    }
  }
}

TEST(ElasticModel, AStretchedStrutPullsItsPlatformJointTowardsTheBase) {
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  DynamicsParameters p = machine.dynamics;
  p.gravity_mm_s2.setZero();
  p.platform = BodyInertia{50.0, Eigen::Vector3d::Zero(), 1e6 * Eigen::Matrix3d::Identity()};
  for (int j = 0; j < 6; ++j) p.struts[j].lower = p.struts[j].upper = StrutPart{};  // the platform alone
  auto model = dynamics::make_elastic_model(*machine.mechanism, p);
  ASSERT_TRUE(model.ok()) << model.error().message;
  const Pose pose = machine.mechanism->home();
  const ActuatorVector lengths = *machine.mechanism->inverse(pose);
  StrutJointPoints ends;
  ASSERT_EQ(machine.mechanism->strut_ends(pose, ends), 6);
  for (int j = 0; j < 6; ++j) {
    SCOPED_TRACE(fmt::format("strut {}", j + 1));
    dynamics::DriveSetpoint drives{lengths, ActuatorVector::Zero(6), {}};
    drives.position_mm[j] -= 0.01;  // the drive holds it 10 µm short: the element is stretched by 10 µm
    dynamics::ElasticWorkspace workspace;
    CoordinateVector accel;
    dynamics::StrutForces forces;
    ASSERT_TRUE(dynamics::elastic_accelerations(*model, pose, CoordinateVector::Zero(6), drives, workspace,
                                                accel, &forces)
                    .ok());
    EXPECT_NEAR(forces.force_N[j], p.struts[j].stiffness_N_mm * 0.01, 1e-9 * forces.force_N[j]);
    // The force on the platform is −F u_j at B_j (u_j from A_j to B_j): a = −(F/m) u_j, and the moment
    // about the tool point (B_j − p) × (−F u_j) turns it with I α.
    const Eigen::Vector3d u = (ends.platform_mm[j] - ends.base_mm[j]).normalized();
    const Eigen::Vector3d force_kg_mm_s2 = -forces.force_N[j] * 1e3 * u;
    EXPECT_LE((accel.head<3>() - force_kg_mm_s2 / 50.0).norm(), 1e-9 * force_kg_mm_s2.norm() / 50.0);
    const Eigen::Vector3d moment = (ends.platform_mm[j] - pose.position_mm).cross(force_kg_mm_s2);
    EXPECT_LE((accel.tail<3>() - moment / 1e6).norm(), 1e-9 * moment.norm() / 1e6);
  }
  // The friction opposes the elongation rate: the platform moving away from strut 1's base at 3 mm/s.
  StrutDynamics strut = p.struts[0];
  const dynamics::ElasticModelOptions options;
  for (auto [damping, beta, expected] :
       {std::tuple{StrutDamping::viscous, 40.0, 120.0}, std::tuple{StrutDamping::quadratic, 0.4, 3.6},
        std::tuple{StrutDamping::coulomb, 30.0, 30.0 * std::tanh(300.0)}}) {
    strut.damping = damping;
    strut.damping_coefficient = beta;
    EXPECT_NEAR(dynamics::damping_force_N(strut, 3.0, options), expected, 1e-12 * expected);
    EXPECT_NEAR(dynamics::damping_force_N(strut, -3.0, options), -expected, 1e-12 * expected);
  }
}

TEST(ElasticModel, TheWideKernelsGiveTheBaselineAccelerations) {
  // The right-hand side's AVX2/FMA kernels (core/wide_kernels.hpp, chosen at run time where the processor has
  // them) against the baseline ones, on random hexapods with random inertial and stiffness parameters, at
  // random poses, rates and drive errors: the same accelerations and forces up to rounding (fused
  // multiply–adds round once where the baseline rounds twice).
  std::mt19937_64 rng(202);
  int compared = 0;
  for (int machine_index = 0; machine_index < 5; ++machine_index) {
    const Machine machine = test::random_hexapod_machine(rng, machine_index);
    const Mechanism& mech = *machine.mechanism;
    for (int trial = 0; trial < 4; ++trial) {
      const DynamicsParameters p = test::random_elastic_parameters(
          rng, 6, trial % 2 == 0 ? StrutDamping::quadratic : StrutDamping::viscous);
      auto model = dynamics::make_elastic_model(mech, p);
      ASSERT_TRUE(model.ok()) << model.error().message;
      PoseVector c = vector_from_pose(mech.convention(), mech.home());
      for (int axis = 0; axis < 6; ++axis)
        c[axis] += axis < 3 ? test::uniform(rng, -10, 10) : test::uniform(rng, -0.05, 0.05);
      const Pose pose = pose_from_vector(mech.convention(), c);
      CoordinateVector rates(6);
      for (int k = 0; k < 6; ++k)
        rates[k] = k < 3 ? test::uniform(rng, -80, 80) : test::uniform(rng, -0.5, 0.5);
      dynamics::DriveSetpoint drives{*mech.inverse(pose), ActuatorVector::Zero(6), {}};
      for (int j = 0; j < 6; ++j) {
        drives.position_mm[j] += test::uniform(rng, -0.02, 0.02);
        drives.rate_mm_s[j] = test::uniform(rng, -5, 5);
      }
      dynamics::ElasticWorkspace workspace;
      CoordinateVector wide, baseline;
      dynamics::StrutForces wide_forces, baseline_forces;
      ASSERT_TRUE(
          dynamics::elastic_accelerations(*model, pose, rates, drives, workspace, wide, &wide_forces).ok());
      {
        const BaselineKernelsOnly baseline_only;
        EXPECT_FALSE(wide_kernels_enabled());
        ASSERT_TRUE(dynamics::elastic_accelerations(*model, pose, rates, drives, workspace, baseline,
                                                    &baseline_forces)
                        .ok());
      }
      EXPECT_LE((wide - baseline).cwiseAbs().maxCoeff(), 1e-9 * baseline.cwiseAbs().maxCoeff());
      EXPECT_LE((wide_forces.force_N - baseline_forces.force_N).cwiseAbs().maxCoeff(),
                1e-12 * baseline_forces.force_N.cwiseAbs().maxCoeff());
      ++compared;
    }
  }
  EXPECT_EQ(compared, 20);
  EXPECT_EQ(wide_kernels_enabled(), wide_kernels_available());
  std::printf("AVX2/FMA kernels %s\n",
              wide_kernels_available() ? "in use" : "not available on this processor");
}

TEST(ElasticModel, MachinesWithoutAnElasticModelSayWhyAndWhere) {
  // No dynamics section at all.
  const Machine glide = test::machine_from_example("examples/machines/hexaglide.yaml");
  auto none = dynamics::make_elastic_model(glide);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("hexaglide.yaml: the machine file has no dynamics: section"),
            std::string::npos)
      << none.error().message;
  EXPECT_EQ(none.error().location.key, "dynamics");
  // Masses but no stiffness for the struts: the file, the section's line and the key.
  std::string text =
      test::kCh5HexapodText +
      "dynamics:\n  platform: {mass_kg: 60}\n  struts:\n    lower: {mass_kg: 15, com_mm: 150}\n";
  const Machine rigid = test::machine_from_text(text, "rigid_struts.yaml");
  auto missing = dynamics::make_elastic_model(rigid);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("rigid_struts.yaml:"), std::string::npos) << missing.error().message;
  EXPECT_NE(missing.error().message.find("dynamics.struts.stiffness_N_mm: not given for strut 1"),
            std::string::npos)
      << missing.error().message;
  EXPECT_EQ(missing.error().location.file, "rigid_struts.yaml");
  EXPECT_GT(missing.error().location.line, 0);
  // A tripod's platform turns its allowed twists with the pose.
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  auto reduced = dynamics::make_elastic_model(*tripod.mechanism, tripod.dynamics);
  ASSERT_FALSE(reduced.ok());
  EXPECT_EQ(reduced.error().code, ErrorCode::unsupported);
  EXPECT_NE(reduced.error().message.find("twist basis"), std::string::npos) << reduced.error().message;
}

}  // namespace
}  // namespace pkm
