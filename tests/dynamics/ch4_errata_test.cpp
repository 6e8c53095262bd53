// The corrected behaviour where the printed formulas of Smirnov 2019, chapter 4, are wrong
// (docs/theory/dynamics.md, §7), pinned on the exact model of src/dynamics:
//  - the printed (116) counts the whole |ω|² of a strut, spin included, and (128) takes the radial speed
//    for |v_C|: the strut parts' and the platform's CoM velocities are the time derivatives of their
//    positions, checked against differences of the positions along a motion;
//  - (127), (132), (140) expand ω in q only, so the rotational inertia never enters the mass matrix, and
//    (107) has no Ṁ terms: the platform's rotational inertia is the rotational block of the mass matrix,
//    and a moving machine has velocity-product terms;
//  - the energy accounting of (86)/(93) (no regeneration: negative work counts as drawn) and the bound (87):
//    lowering a platform and raising it again draws at least twice its change of potential energy without
//    recovery, once when braking is free, and once with recovery between drives.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rotation.hpp"
#include "dynamics/equations_of_motion.hpp"
#include "dynamics/rigid_dynamics.hpp"
#include "dynamics/run_dynamics.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

/// The ch5 hexapod at a tilted pose moving with a general twist.
struct Ch5Motion {
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  Pose pose;
  Eigen::Matrix<double, 6, 1> twist;
  Ch5Motion() {
    pose = test::abc_pose(12, -8, 0, 4, -3, 6);
    pose.position_mm += machine.mechanism->home().position_mm;
    twist << 40, -25, 30, 0.3, -0.2, 0.4;
  }
  /// The pose after moving with the twist for `t` seconds (constant twist: exp of the rotation vector).
  Pose after(double t) const {
    Pose p;
    p.position_mm = pose.position_mm + twist.head<3>() * t;
    p.rotation = rotation_from_rotation_vector(twist.tail<3>() * t) * pose.rotation;
    return p;
  }
};

TEST(Ch4Errata, StrutPartsMoveWithTheDerivativesOfTheirPositionsNotTheWholeAngularVelocity) {
  const Ch5Motion m;
  const Mechanism& mech = *m.machine.mechanism;
  DynamicsParameters p;
  p.strut_count = 6;
  for (int j = 0; j < 6; ++j) {
    p.struts[j].lower = {15.0, 150.0, 0.0};
    p.struts[j].upper = {10.0, 120.0, 0.0};
  }
  // ½ Σ m |ċ|² with ċ from central differences of the parts' centres of mass along the motion.
  auto centres = [&](double t) {
    StrutJointPoints ends;
    EXPECT_EQ(mech.strut_ends(m.after(t), ends), 6);
    std::array<Eigen::Vector3d, 12> c;
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d u = (ends.platform_mm[j] - ends.base_mm[j]).normalized();
      c[2 * j] = ends.base_mm[j] + 150.0 * u;
      c[2 * j + 1] = ends.platform_mm[j] - 120.0 * u;
    }
    return c;
  };
  const double h = 1e-5;
  const auto ahead = centres(h), behind = centres(-h);
  double expected_J = 0.0;
  for (int k = 0; k < 12; ++k)
    expected_J += 0.5 * (k % 2 == 0 ? 15.0 : 10.0) * ((ahead[k] - behind[k]) / (2 * h)).squaredNorm() * 1e-6;
  dynamics::PlatformMotion motion;
  motion.pose = m.pose;
  motion.velocity_mm_s = m.twist.head<3>();
  motion.angular_velocity_rad_s = m.twist.tail<3>();
  const double energy_J = *dynamics::kinetic_energy_J(mech, p, motion);
  EXPECT_NEAR(energy_J, expected_J, 1e-8 * expected_J);
}

TEST(Ch4Errata, ThePlatformsRotationalInertiaIsInTheMassMatrix) {
  const Ch5Motion m;
  const Mechanism& mech = *m.machine.mechanism;
  DynamicsParameters p;
  p.strut_count = 6;
  p.platform.mass_kg = 60.0;
  p.platform.com_mm.setZero();  // at the tool point: no coupling of translation and rotation
  p.platform.inertia_kg_mm2 << 5e5, 2e4, -1e4, 2e4, 4e5, 3e4, -1e4, 3e4, 6e5;
  TwistBasis basis;
  ASSERT_TRUE(dynamics::platform_twist_basis(mech, basis));
  auto at_rest = dynamics::equations_of_motion(mech, p, m.pose, basis, dynamics::Twist::Zero());
  ASSERT_TRUE(at_rest.ok()) << at_rest.error().message;
  const Eigen::Matrix3d rotational =
      m.pose.rotation * p.platform.inertia_kg_mm2 * m.pose.rotation.transpose();
  EXPECT_LE((at_rest->mass.bottomRightCorner(3, 3) - rotational).cwiseAbs().maxCoeff(), 1e-9 * 6e5);
  EXPECT_LE((at_rest->mass.topLeftCorner(3, 3) - 60.0 * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
            1e-12);
  EXPECT_LE(at_rest->bias.cwiseAbs().maxCoeff(), 1e-12);
  // Turning, the platform needs the gyroscopic moment ω × I ω (a velocity-product term).
  auto turning = dynamics::equations_of_motion(mech, p, m.pose, basis, m.twist);
  ASSERT_TRUE(turning.ok());
  const Eigen::Vector3d w = m.twist.tail<3>();
  const Eigen::Vector3d gyroscopic = w.cross(rotational * w);
  EXPECT_LE((turning->bias.tail(3) - gyroscopic).cwiseAbs().maxCoeff(), 1e-9 * gyroscopic.norm());
}

TEST(Ch4Errata, NegativeWorkIsDrawnWithoutRecoveryAndTheEnergyIsAtLeastTheRequiredWork) {
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  DynamicsParameters& p = machine.dynamics;
  p = DynamicsParameters{};
  p.strut_count = 6;
  p.platform.mass_kg = 50.0;
  p.line = 1;
  // Down by 20 mm and back up over 4 s, slowly: the platform's potential energy changes by m g Δz each way.
  const double depth_mm = 20.0, period_s = 4.0, h = 1e-3;
  dynamics::RunDynamics run(machine, h, {});
  const Pose home = machine.mechanism->home();
  for (long k = 0; k <= static_cast<long>(period_s / h); ++k) {
    const double t = static_cast<double>(k) * h;
    Pose pose = home;
    pose.position_mm.z() -= 0.5 * depth_mm * (1.0 - std::cos(2 * kPi * t / period_s));
    ASSERT_TRUE(run.add(t, 1, pose).ok());
  }
  ASSERT_TRUE(run.finish().ok());
  const dynamics::EnergyTotals& e = run.summary().energy;
  const double lift_J = 50.0 * 9.81 * depth_mm * 1e-3;
  EXPECT_NEAR(e.no_recovery_J, 2.0 * lift_J, 0.02 * lift_J);  // lowering draws as much as lifting
  EXPECT_NEAR(e.braking_free_J, lift_J, 0.02 * lift_J);       // lowering is free
  EXPECT_NEAR(e.recovery_J, lift_J, 0.02 * lift_J);           // the required work (87)
  EXPECT_GE(e.no_recovery_J, e.braking_free_J);
  EXPECT_GE(e.braking_free_J, e.recovery_J - 1e-12);
}

}  // namespace
}  // namespace pkm
