// The weight of platform and struts as a wrench about the tool point (statics/gravity.hpp).
#include "statics/gravity.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "core/units.hpp"
#include "machine/hexapod.hpp"
#include "statics/actuator_forces.hpp"
#include "test_support.hpp"

namespace pkm::statics {
namespace {

TEST(StaticsGravity, WeightUnits) {
  // 1 kg under 9810 mm/s² weighs 9.81 N.
  EXPECT_TRUE(weight_N(1.0, Eigen::Vector3d(0, 0, -9810)).isApprox(Eigen::Vector3d(0, 0, -9.81)));
}

TEST(StaticsGravity, OffsetCentreOfMassGivesItsMoment) {
  MassProperties masses;
  masses.platform_kg = 10.0;
  masses.platform_com_mm = Eigen::Vector3d(100, 0, 0);  // tool frame
  Pose pose;
  pose.position_mm = Eigen::Vector3d(5, 6, 700);
  pose.rotation = rot_z(rad_from_deg(90.0));  // the centre of mass is then 100 mm along +y of the tool point
  const Wrench w = gravity_wrench(masses, pose, nullptr, 0);
  EXPECT_TRUE(w.force_N.isApprox(Eigen::Vector3d(0, 0, -98.1)));
  // (0, 100, 0) × (0, 0, −98.1) = (−9810, 0, 0) N·mm.
  EXPECT_NEAR(w.moment_Nmm.x(), -9810.0, 1e-9);
  EXPECT_NEAR(w.moment_Nmm.y(), 0.0, 1e-9);
  EXPECT_NEAR(w.moment_Nmm.z(), 0.0, 1e-9);
}

TEST(StaticsGravity, HalfOfEachStrutAtItsPlatformJoint) {
  MassProperties masses;
  masses.strut_kg = 4.0;
  masses.gravity_mm_s2 = Eigen::Vector3d(0, -9810, 0);  // gravity along −y (a machine lying on its side)
  Pose pose;
  StrutJointPoints struts;
  struts.platform_mm[0] = Eigen::Vector3d(0, 0, 200);
  struts.platform_mm[1] = Eigen::Vector3d(0, 0, -200);
  struts.platform_mm[2] = Eigen::Vector3d(50, 0, 0);
  const Wrench w = gravity_wrench(masses, pose, &struts, 3);
  const Eigen::Vector3d half(0, -2.0 * 9.81, 0);
  EXPECT_TRUE(w.force_N.isApprox(3.0 * half));
  // Struts 1 and 2 cancel; strut 3: (50, 0, 0) × (0, −19.62, 0) = (0, 0, −981).
  EXPECT_TRUE(w.moment_Nmm.isApprox(Eigen::Vector3d(0, 0, -981.0)));
  // Without struts only the (zero) platform counts.
  EXPECT_TRUE(gravity_wrench(masses, pose, nullptr, 0).force_N.isZero());
}

TEST(StaticsGravity, HexapodAtHomeHoldsThePlatformWeight) {
  const std::string text =
      test::kCh5HexapodText + "masses: {platform_kg: 60, platform_com_mm: [20, -10, -100]}\n";
  const Machine machine = test::machine_from_text(text);
  const auto& hexapod = dynamic_cast<const Hexapod&>(*machine.mechanism);
  auto gravity = machine_gravity_wrench(machine, hexapod.home());
  ASSERT_TRUE(gravity.ok()) << gravity.error().message;
  auto forces = actuator_forces(hexapod, hexapod.home(), *gravity);
  ASSERT_TRUE(forces.ok()) << forces.error().message;
  // The struts' forces on the platform, P_j u_j, balance the weight: vertically Σ P_j u_jz = m g.
  StrutJointPoints joints;
  ASSERT_EQ(hexapod.strut_joints(hexapod.home(), joints), 6);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d u = (joints.platform_mm[j] - joints.base_mm[j]).normalized();
    total += (*forces)[j] * u;
    moment += (joints.platform_mm[j] - hexapod.home().position_mm).cross((*forces)[j] * u);
    EXPECT_GT((*forces)[j], 0.0) << "a standing hexapod's struts push the platform up";
  }
  EXPECT_NEAR(total.z(), 60.0 * 9.81, 1e-9 * 588.6);
  EXPECT_NEAR(total.x(), 0.0, 1e-9);
  EXPECT_NEAR(total.y(), 0.0, 1e-9);
  EXPECT_TRUE((moment + gravity->moment_Nmm).isZero(1e-6));
}

TEST(StaticsGravity, MachineWrenchAddsHalfStrutsAtTheirJoints) {
  const std::string text = test::kCh5HexapodText + "masses: {platform_kg: 0, strut_kg: 10}\n";
  const Machine machine = test::machine_from_text(text);
  auto gravity = machine_gravity_wrench(machine, machine.mechanism->home());
  ASSERT_TRUE(gravity.ok());
  EXPECT_TRUE(gravity->force_N.isApprox(Eigen::Vector3d(0, 0, -6 * 5 * 9.81)));
}

}  // namespace
}  // namespace pkm::statics
