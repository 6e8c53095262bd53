// Actuator forces from a load (Smirnov 2019, (73)/(91)): the virtual-work balance for every shipped machine,
// the hexapod's fast path against the generic one, the planar case against the coefficients of (73), and
// singular or unreachable poses.
#include "statics/actuator_forces.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <string>

#include "core/units.hpp"
#include "machine/hexapod.hpp"
#include "machine/planar3.hpp"
#include "statics_test_support.hpp"

namespace pkm::statics {
namespace {

using test::expect_virtual_work_balance;
using test::random_small_motion;
using test::random_wrench;
using test::uniform;

/// A pose near home: controlled coordinates moved by up to ± `mm` and ± `deg`, then completed.
Result<Pose> pose_near_home(const Mechanism& mechanism, std::mt19937_64& rng, double mm, double deg) {
  PoseVector q = vector_from_pose(mechanism.convention(), mechanism.home());
  const AxisMask mask = mechanism.controlled_axes();
  for (int axis = 0; axis < 6; ++axis) {
    if (mask.controlled[axis]) q[axis] += uniform(rng, -1.0, 1.0) * (axis < 3 ? mm : rad_from_deg(deg));
  }
  return mechanism.complete_pose(pose_from_vector(mechanism.convention(), q));
}

void check_virtual_work(const std::string& example, int poses, double mm, double deg) {
  SCOPED_TRACE(example);
  const Machine machine = test::machine_from_example(example);
  const Mechanism& mechanism = *machine.mechanism;
  std::mt19937_64 rng(2019);
  for (int k = 0; k < poses; ++k) {
    auto pose = k == 0 ? mechanism.complete_pose(mechanism.home()) : pose_near_home(mechanism, rng, mm, deg);
    ASSERT_TRUE(pose.ok()) << pose.error().message;
    const Wrench load = random_wrench(rng);
    auto forces = actuator_forces(mechanism, *pose, load);
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    ASSERT_EQ(forces->size(), mechanism.actuator_count());
    for (int m = 0; m < 5; ++m) {
      expect_virtual_work_balance(*forces, random_small_motion(mechanism, *pose, rng), load);
    }
  }
}

TEST(StaticsForces, HexapodVirtualWork) {
  check_virtual_work("examples/machines/hexapod_ch3.yaml", 20, 30.0, 8.0);
  check_virtual_work("examples/machines/hexapod_ch3_delta30.yaml", 20, 30.0, 8.0);
  check_virtual_work("examples/machines/hexapod_ch5.yaml", 10, 30.0, 8.0);
}

TEST(StaticsForces, PlanarVirtualWork) {
  check_virtual_work("examples/machines/planar3.yaml", 20, 30.0, 8.0);
  check_virtual_work("examples/machines/planar2.yaml", 10, 30.0, 0.0);
}

TEST(StaticsForces, ReducedDofVirtualWorkThroughCompletePose) {
  // x, y and the yaw of the tripod, the tricept's orientation, follow the controlled coordinates.
  check_virtual_work("examples/machines/tripod.yaml", 20, 30.0, 5.0);
  check_virtual_work("examples/machines/tricept.yaml", 20, 60.0, 0.0);
}

TEST(StaticsForces, OtherMechanismsVirtualWork) {
  check_virtual_work("examples/machines/hexaglide.yaml", 5, 10.0, 3.0);
  check_virtual_work("examples/machines/triglide.yaml", 5, 10.0, 0.0);
  check_virtual_work("examples/machines/rotopod.yaml", 5, 10.0, 3.0);
  check_virtual_work("examples/machines/hexapod_refined.yaml", 5, 10.0, 3.0);
}

TEST(StaticsForces, HexapodFastPathEqualsGenericPath) {
  for (const char* example :
       {"examples/machines/hexapod_ch3.yaml", "examples/machines/hexapod_ch3_delta30.yaml",
        "examples/machines/hexapod_ch5.yaml"}) {
    SCOPED_TRACE(example);
    const Machine machine = test::machine_from_example(example);
    const auto& hexapod = dynamic_cast<const Hexapod&>(*machine.mechanism);
    std::mt19937_64 rng(7);
    for (int k = 0; k < 50; ++k) {
      auto pose = pose_near_home(hexapod, rng, 40.0, 10.0);
      ASSERT_TRUE(pose.ok());
      const Wrench load = random_wrench(rng);
      auto generic = actuator_forces(hexapod, *pose, load);
      ASSERT_TRUE(generic.ok()) << generic.error().message;
      double fast[6];
      ASSERT_TRUE(twist_actuator_forces(hexapod, *pose, load, fast));
      for (int j = 0; j < 6; ++j) EXPECT_NEAR(fast[j], (*generic)[j], 1e-9 * generic->cwiseAbs().maxCoeff());
    }
  }
}

TEST(StaticsForces, PlanarEqualsTheSeedsCoefficients73) {
  const Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  const auto& planar = dynamic_cast<const Planar3&>(*machine.mechanism);
  std::mt19937_64 rng(73);
  for (int k = 0; k < 30; ++k) {
    const double xc = uniform(rng, -40, 40), yc = uniform(rng, -40, 40),
                 phi = rad_from_deg(uniform(rng, 5, 30));
    const Pose pose = pose_from_planar(Eigen::Vector3d(xc, yc, phi));
    // (73): a_1j, a_2j the strut direction, a_3j its moment arm about C; Σ_j a_ij P_j = −(P_x, P_y, M).
    Eigen::Matrix3d a;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d& base = planar.geometry().base_joints_mm[j];
      const Eigen::Vector3d b = pose.to_base(Eigen::Vector3d(
          planar.geometry().platform_joints_mm[j].x(), planar.geometry().platform_joints_mm[j].y(), 0.0));
      const double xa = base.x(), ya = base.y(), xb = b.x(), yb = b.y();
      const double length = std::hypot(xb - xa, yb - ya);
      a(0, j) = (xb - xa) / length;
      a(1, j) = (yb - ya) / length;
      a(2, j) = ((xb - xa) * yc - (yb - ya) * xc + xa * yb - xb * ya) / length;
    }
    Wrench load = random_wrench(rng);
    const Eigen::Vector3d seed =
        a.lu().solve(-Eigen::Vector3d(load.force_N.x(), load.force_N.y(), load.moment_Nmm.z()));
    auto forces = actuator_forces(planar, pose, load);
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    for (int j = 0; j < 3; ++j) EXPECT_NEAR((*forces)[j], seed[j], 1e-9 * seed.cwiseAbs().maxCoeff());
    // The load out of the plane is carried by the planar guide, not by the struts.
    load.force_N.z() += 5000.0;
    load.moment_Nmm.x() -= 3e5;
    auto with_out_of_plane = actuator_forces(planar, pose, load);
    ASSERT_TRUE(with_out_of_plane.ok());
    EXPECT_TRUE(with_out_of_plane->isApprox(*forces, 1e-12));
  }
}

TEST(StaticsForces, PushingStrutsHaveAPositiveForce) {
  // A hexapod standing on its base, pressed down at the tool point: every strut is in compression.
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch3.yaml");
  auto forces = actuator_forces(*machine.mechanism, machine.mechanism->home(),
                                Wrench{Eigen::Vector3d(0, 0, -600), Eigen::Vector3d::Zero()});
  ASSERT_TRUE(forces.ok());
  for (int j = 0; j < 6; ++j) EXPECT_GT((*forces)[j], 0.0) << "strut " << j + 1;
}

TEST(StaticsForces, SingularPlanarPoseIsAnError) {
  // The layout of Smirnov 2019, §3.3: similar triangles at the same polar angles are singular at φ = 0
  // everywhere (its Fig. 71).
  const Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  auto forces = actuator_forces(*machine.mechanism, pose_from_planar(Eigen::Vector3d(-10, 10, 0.0)),
                                Wrench{Eigen::Vector3d(100, 0, 0), Eigen::Vector3d::Zero()});
  ASSERT_FALSE(forces.ok());
  EXPECT_EQ(forces.error().code, ErrorCode::singular);
  EXPECT_NE(forces.error().message.find("singular"), std::string::npos) << forces.error().message;
}

TEST(StaticsForces, SingularHexapodPoseIsAnErrorOnBothPaths) {
  // Every strut vertical: no strut can resist a horizontal force.
  HexapodGeometry g;
  for (int j = 0; j < 6; ++j) {
    const double angle = rad_from_deg(60.0 * j + 10.0 * (j % 2));
    g.base_joints_mm[j] = Eigen::Vector3d(300 * std::cos(angle), 300 * std::sin(angle), 0.0);
    g.platform_joints_mm[j] = g.base_joints_mm[j];
  }
  Pose home;
  home.position_mm = Eigen::Vector3d(0, 0, 500);
  const Hexapod hexapod(g, AngleConvention::abc, home);
  const Wrench load{Eigen::Vector3d(100, 0, -100), Eigen::Vector3d::Zero()};
  auto forces = actuator_forces(hexapod, home, load);
  ASSERT_FALSE(forces.ok());
  EXPECT_EQ(forces.error().code, ErrorCode::singular);
  double fast[6];
  EXPECT_FALSE(twist_actuator_forces(hexapod, home, load, fast));
}

TEST(StaticsForces, UnreachablePoseIsAnError) {
  const Machine machine = test::machine_from_example("examples/machines/tricept.yaml");
  Pose below;
  below.position_mm = Eigen::Vector3d(0, 0, -200);  // below the central joint O
  auto forces = actuator_forces(*machine.mechanism, below, Wrench{});
  ASSERT_FALSE(forces.ok());
  EXPECT_EQ(forces.error().code, ErrorCode::unreachable);
}

}  // namespace
}  // namespace pkm::statics
