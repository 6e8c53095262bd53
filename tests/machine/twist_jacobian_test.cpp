// Mechanism::twist_jacobian against Mechanism::jacobian on every shipped machine (a cross-algorithm check):
// the coordinate Jacobian is the twist Jacobian times the twist of each controlled coordinate,
// J_c = J_t · T_c (Mechanism::controlled_twists); and T_c of the mechanisms whose dependent coordinates move
// (tripod, tricept: their constraints differentiated) against central differences of complete_pose.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "core/rotation.hpp"
#include "statics/actuator_forces.hpp"
#include "statics/coordinate_twist.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

TEST(TwistJacobian, TimesTheControlledTwistsIsTheCoordinateJacobianOnEveryShippedMachine) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml",
        "tripod.yaml", "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    SCOPED_TRACE(file);
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis]) c[axis] += axis < 3 ? 2.0 : 0.01;
    }
    const Pose pose = *mech.complete_pose(pose_from_vector(mech.convention(), c));
    JacobianMatrix twist;
    ASSERT_TRUE(mech.twist_jacobian(pose, twist));
    ASSERT_EQ(twist.rows(), mech.actuator_count());
    ASSERT_EQ(twist.cols(), 6);
    const auto coordinate = mech.jacobian(pose);
    ASSERT_TRUE(coordinate.ok()) << coordinate.error().message;
    const auto basis = statics::controlled_twist_basis(mech, pose);
    ASSERT_TRUE(basis.ok()) << basis.error().message;
    const JacobianMatrix product = twist * *basis;
    constexpr double kAgreement = 1e-10;
    EXPECT_LE((product - *coordinate).cwiseAbs().maxCoeff(), kAgreement * coordinate->cwiseAbs().maxCoeff())
        << "twist·T_c:\n"
        << product << "\njacobian:\n"
        << *coordinate;
  }
}

// Mechanism::strut_state (one call for the dynamics' right-hand sides; the hexapod overrides it with one pass
// over its struts) gives what strut_ends, actuator_values and twist_jacobian give, at random poses of every
// shipped machine with struts; and −1 where actuator_values fails (a strut of zero length).
TEST(TwistJacobian, StrutStateEqualsTheThreeSeparateCalls) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> shift(-15.0, 15.0), tilt(-0.05, 0.05);
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_ch3_delta30.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml",
        "tripod.yaml", "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml", "planar3.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    const AxisMask mask = mech.controlled_axes();
    for (int trial = 0; trial < 10; ++trial) {
      SCOPED_TRACE(std::string(file) + " trial " + std::to_string(trial));
      PoseVector c = vector_from_pose(mech.convention(), mech.home());
      for (int axis = 0; axis < 6; ++axis) {
        if (mask.controlled[axis]) c[axis] += axis < 3 ? shift(rng) : tilt(rng);
      }
      const auto completed = mech.complete_pose(pose_from_vector(mech.convention(), c));
      ASSERT_TRUE(completed.ok()) << completed.error().message;
      StrutJointPoints ends, fused_ends;
      std::array<double, kMaxActuators> values{}, fused_values{};
      JacobianMatrix twist, fused_twist;
      const int struts = mech.strut_ends(*completed, ends);
      ASSERT_TRUE(mech.actuator_values(*completed, values.data()));
      ASSERT_TRUE(mech.twist_jacobian(*completed, twist));
      ASSERT_EQ(mech.strut_state(*completed, fused_ends, fused_values.data(), fused_twist), struts);
      constexpr double kRounding = 1e-12;
      for (int j = 0; j < struts; ++j) {
        EXPECT_LE((fused_ends.base_mm[j] - ends.base_mm[j]).norm(), kRounding * 1e3) << j;
        EXPECT_LE((fused_ends.platform_mm[j] - ends.platform_mm[j]).norm(), kRounding * 1e3) << j;
      }
      for (int a = 0; a < mech.actuator_count(); ++a)
        EXPECT_NEAR(fused_values[a], values[a], kRounding * 1e3);
      ASSERT_EQ(fused_twist.rows(), twist.rows());
      ASSERT_EQ(fused_twist.cols(), twist.cols());
      EXPECT_LE((fused_twist - twist).cwiseAbs().maxCoeff(), kRounding * (1.0 + twist.cwiseAbs().maxCoeff()));
    }
  }
  // A platform joint on its base joint: the hexapod's strut 1 has zero length.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *m.mechanism;
  StrutJointPoints ends;
  mech.strut_ends(mech.home(), ends);
  Pose collapsed = mech.home();
  collapsed.position_mm += ends.base_mm[0] - ends.platform_mm[0];
  std::array<double, kMaxActuators> values{};
  JacobianMatrix twist;
  EXPECT_EQ(mech.strut_state(collapsed, ends, values.data(), twist), -1);
}

// Column c of T_c against the central difference of complete_pose over ±h in controlled coordinate c (the
// twist of R₊R₋ᵀ = exp([ω]× 2h) + O(h³)), at random poses around home.
TEST(TwistJacobian, ControlledTwistsAreTheDerivativesOfCompletePose) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> shift(-20.0, 20.0), tilt(-0.08, 0.08);
  for (const char* file : {"tripod.yaml", "tricept.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    const AxisMask mask = mech.controlled_axes();
    for (int trial = 0; trial < 20; ++trial) {
      SCOPED_TRACE(std::string(file) + " trial " + std::to_string(trial));
      PoseVector c = vector_from_pose(mech.convention(), mech.home());
      for (int axis = 0; axis < 6; ++axis) {
        if (mask.controlled[axis]) c[axis] += axis < 3 ? shift(rng) : tilt(rng);
      }
      auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
      ASSERT_TRUE(pose.ok()) << pose.error().message;
      TwistBasis basis;
      ASSERT_TRUE(mech.controlled_twists(*pose, basis));
      const PoseVector centre = vector_from_pose(mech.convention(), *pose);
      int column = 0;
      for (int axis = 0; axis < 6; ++axis) {
        if (!mask.controlled[axis]) continue;
        const double h = axis < 3 ? 1e-3 : 1e-5;
        Pose side[2];
        for (int k = 0; k < 2; ++k) {
          PoseVector q = centre;
          q[axis] += k == 0 ? h : -h;
          auto completed = mech.complete_pose(pose_from_vector(mech.convention(), q));
          ASSERT_TRUE(completed.ok());
          side[k] = *completed;
        }
        Eigen::Matrix<double, 6, 1> difference;
        difference << (side[0].position_mm - side[1].position_mm) / (2 * h),
            rotation_vector_from_rotation(side[0].rotation * side[1].rotation.transpose()) / (2 * h);
        const double scale = std::max(1.0, basis.col(column).cwiseAbs().maxCoeff());
        EXPECT_LE((difference - basis.col(column)).cwiseAbs().maxCoeff(), 1e-7 * scale)
            << "coordinate " << axis << ": analytic " << basis.col(column).transpose() << ", differences "
            << difference.transpose();
        ++column;
      }
    }
  }
}

// The fixed-size statics from the twist Jacobian (redundancy's hot path) gives the forces of the generic
// solve in controlled coordinates on every six-actuator, six-coordinate machine.
TEST(TwistJacobian, TwistStaticsAgreeWithTheGenericSolve) {
  for (const char* file : {"hexapod_ch5.yaml", "hexapod_refined.yaml", "hexaglide.yaml", "rotopod.yaml"}) {
    SCOPED_TRACE(file);
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    c[0] += 3.0;
    c[4] += 0.02;
    const Pose pose = *mech.complete_pose(pose_from_vector(mech.convention(), c));
    const statics::Wrench load{Eigen::Vector3d(100, -50, -600), Eigen::Vector3d(1e3, 2e4, -5e3)};
    double fast[6];
    ASSERT_TRUE(statics::twist_actuator_forces(mech, pose, load, fast));
    const auto generic = statics::actuator_forces(mech, pose, load);
    ASSERT_TRUE(generic.ok()) << generic.error().message;
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(fast[j], (*generic)[j], 1e-9 * generic->cwiseAbs().maxCoeff()) << j;
  }
}

}  // namespace
}  // namespace pkm
