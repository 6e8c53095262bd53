// Mechanism::twist_jacobian against Mechanism::jacobian on every shipped machine (a cross-algorithm check):
// the coordinate Jacobian is the twist Jacobian times the twist of each controlled coordinate,
// J_c = J_t · T_c (statics/coordinate_twist.hpp: analytic for six-coordinate and planar mechanisms, central
// differences of complete_pose for the tripod and tricept).
#include <gtest/gtest.h>

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
    // Central differences (tripod, tricept) leave ~1e-10 relative; the analytic cases agree to round-off.
    constexpr double kAgreement = 1e-8;
    EXPECT_LE((product - *coordinate).cwiseAbs().maxCoeff(), kAgreement * coordinate->cwiseAbs().maxCoeff())
        << "twist·T_c:\n"
        << product << "\njacobian:\n"
        << *coordinate;
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
