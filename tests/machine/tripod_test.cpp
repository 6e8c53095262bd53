// Spatial 3-RPS tripod: pose completion on the revolute planes (31), IK/FK round trips on random geometries,
// the Jacobian against finite differences, assembly modes, and machine-file validation.
#include "machine/tripod.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <regex>
#include <string>

#include "core/units.hpp"
#include "io/pose_input.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

constexpr double kDeg = kPi / 180.0;

std::string tripod_yaml(const std::string& angles = "abc", const std::string& axes = "",
                        const std::string& extra = "") {
  const std::string default_axes =
      "base_axes:\n"
      "  - [-1, 0, 0]\n"
      "  - [0.5, -0.8660254037844386, 0]\n"
      "  - [0.5, 0.8660254037844386, 0]\n";
  return "type: tripod\n"
         "angles: " +
         angles +
         "\n"
         "base_joints:\n"
         "  - [0, 400, 0]\n"
         "  - [-346.41016151377545, -200, 0]\n"
         "  - [346.41016151377545, -200, 0]\n" +
         (axes.empty() ? default_axes : axes) +
         "platform_joints:\n"
         "  - [0, 200, 0]\n"
         "  - [-173.20508075688772, -100, 0]\n"
         "  - [173.20508075688772, -100, 0]\n" +
         extra;
}

/// 1/|M⁻¹|_F: within a factor √3 of the smallest singular value (a conditioning test without an SVD).
double tripod_smallest_singular_value(const Eigen::Matrix3d& m) {
  return std::abs(m.determinant()) > 0.0 ? 1.0 / m.inverse().norm() : 0.0;
}

std::string tripod_load_error(const std::string& yaml, const std::string& name = "bad_tripod.yaml") {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok()) << "expected " << name << " to be rejected";
  return machine ? std::string() : machine.error().message;
}

/// Joints near 90°, 210°, 330° on random circles, axes near the tangents (so the yaw constraint has room),
/// random heights; rejected until the home is reachable and well away from singularities.
struct RandomTripod {
  TripodGeometry geometry;
  PoseVector home;
};

RandomTripod random_tripod(std::mt19937_64& rng, AngleConvention convention) {
  for (;;) {
    RandomTripod t;
    const double base_radius = test::uniform(rng, 300, 500), platform_radius = test::uniform(rng, 120, 250);
    for (int j = 0; j < 3; ++j) {
      const double angle = (90.0 + 120.0 * j + test::uniform(rng, -10, 10)) * kDeg;
      const double axis_angle = angle + (90.0 + test::uniform(rng, -8, 8)) * kDeg;
      const double platform_angle = (90.0 + 120.0 * j + test::uniform(rng, -10, 10)) * kDeg;
      t.geometry.base_joints_mm[j] = Eigen::Vector3d(
          base_radius * std::cos(angle), base_radius * std::sin(angle), test::uniform(rng, -20, 20));
      t.geometry.base_axes[j] = Eigen::Vector3d(std::cos(axis_angle), std::sin(axis_angle), 0.0);
      t.geometry.platform_joints_mm[j] = Eigen::Vector3d(
          platform_radius * std::cos(platform_angle), platform_radius * std::sin(platform_angle),
          test::uniform(rng, -10, 10) - 80.0);  // tool point 80 mm above the joint plane
    }
    t.home = PoseVector::Zero();
    t.home[2] = test::uniform(rng, 1.3, 1.8) * base_radius;
    auto tripod = Tripod::create(t.geometry, convention, t.home);
    if (!tripod) continue;
    auto j = tripod->jacobian(tripod->home());
    if (!j || tripod_smallest_singular_value(*j) < 0.05) continue;
    return t;
  }
}

/// A random pose of the controlled coordinates near home (z ± 150 mm, tilts ± 15°), dependents left at zero.
Pose random_controlled_pose(std::mt19937_64& rng, const Tripod& tripod) {
  PoseVector c = PoseVector::Zero();
  const PoseVector home = vector_from_pose(tripod.convention(), tripod.home());
  const AxisMask mask = tripod.controlled_axes();
  for (int i = 0; i < 6; ++i) {
    if (!mask.controlled[i]) continue;
    c[i] = i < 3 ? home[i] + test::uniform(rng, -150, 150) : test::uniform(rng, -15, 15) * kDeg;
  }
  return pose_from_vector(tripod.convention(), c);
}

TEST(TripodFile, ExampleLoadsWithACompleteHome) {
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  ASSERT_EQ(machine.mechanism->type(), MechanismType::tripod);
  const auto& tripod = dynamic_cast<const Tripod&>(*machine.mechanism);
  EXPECT_LT(tripod.plane_residuals_mm(tripod.home()).cwiseAbs().maxCoeff(), 1e-9);
  // Symmetric layout: the home is straight above the base centre; the struts are 100 mm below the tool point.
  EXPECT_LT(tripod.home().position_mm.head<2>().norm(), 1e-9);
  const ActuatorVector q = *tripod.inverse(tripod.home());
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(q[j], std::hypot(200.0, 700.0), 1e-9);
  EXPECT_EQ(controlled_coordinate_names(tripod), (std::vector<std::string>{"z", "A", "B"}));
}

TEST(TripodFile, DefaultHomeIsMidRange) {
  const Machine machine =
      test::machine_from_text(tripod_yaml("krylov", "", "limits: {actuator_min: 500, actuator_max: 900}\n"));
  const ActuatorVector q = *machine.mechanism->inverse(machine.mechanism->home());
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(q[j], 700.0, 1e-6);
  EXPECT_EQ(controlled_coordinate_names(*machine.mechanism),
            (std::vector<std::string>{"z", "theta", "gamma"}));
}

TEST(Tripod, CompletePoseSatisfiesTheRevolutePlanesAndKeepsTheControlledCoordinates) {
  std::mt19937_64 rng(31);
  for (AngleConvention convention : {AngleConvention::abc, AngleConvention::krylov}) {
    for (int g = 0; g < 5; ++g) {
      const RandomTripod t = random_tripod(rng, convention);
      const Tripod tripod = *Tripod::create(t.geometry, convention, t.home);
      const AxisMask mask = tripod.controlled_axes();
      for (int i = 0; i < 200; ++i) {
        const Pose input = random_controlled_pose(rng, tripod);
        auto complete = tripod.complete_pose(input);
        ASSERT_TRUE(complete) << complete.error().message;
        EXPECT_LT(tripod.plane_residuals_mm(*complete).cwiseAbs().maxCoeff(), 1e-9);
        const PoseVector before = vector_from_pose(convention, input),
                         after = vector_from_pose(convention, *complete);
        for (int k = 0; k < 6; ++k) {
          if (mask.controlled[k]) {
            EXPECT_NEAR(after[k], before[k], 1e-12) << "coordinate " << k;
          }
        }
        // Completing again changes nothing (the dependents do not feed back).
        const Pose again = *tripod.complete_pose(*complete);
        EXPECT_LT(pose_distance(again, *complete).position_mm, 1e-9);
        EXPECT_LT(pose_distance(again, *complete).rotation_rad, 1e-12);
      }
    }
  }
}

TEST(Tripod, EachStrutStaysInItsRevolutePlaneAlongTheJointAngle) {
  // B_j(t) = A_j + L (cos t·e_z + sin t·w_j) lies in the plane (31) for every t and has |B_j − A_j| = L.
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  const auto& tripod = dynamic_cast<const Tripod&>(*machine.mechanism);
  for (int j = 0; j < 3; ++j) {
    for (double t : {-1.2, -0.3, 0.0, 0.4, 2.5}) {
      const Eigen::Vector3d b = tripod.joint_at(j, 640.0, t);
      EXPECT_NEAR(tripod.geometry().base_axes[j].dot(b - tripod.geometry().base_joints_mm[j]), 0.0, 1e-12);
      EXPECT_NEAR((b - tripod.geometry().base_joints_mm[j]).norm(), 640.0, 1e-12);
      EXPECT_NEAR(tripod.joint_angle_of(j, b), t, 1e-12);
    }
  }
}

TEST(Tripod, InverseForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(2019);
  FkOptions options;
  options.tolerance_mm = 1e-11;
  // Six geometries, alternating abc and krylov, 1000 poses each.
  for (int g = 0; g < 6; ++g) {
    const AngleConvention convention = g % 2 == 0 ? AngleConvention::abc : AngleConvention::krylov;
    const RandomTripod t = random_tripod(rng, convention);
    const Tripod tripod = *Tripod::create(t.geometry, convention, t.home);
    int max_iterations = 0;
    for (int i = 0; i < 1000; ++i) {
      const Pose truth = *tripod.complete_pose(random_controlled_pose(rng, tripod));
      const ActuatorVector q = *tripod.inverse(truth);
      auto fk = tripod.forward(q, tripod.home(), options);
      ASSERT_TRUE(fk) << "geometry " << g << " pose " << i << ": " << fk.error().message;
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-9) << "geometry " << g << " pose " << i;
      EXPECT_LT(d.rotation_rad, 1e-11) << "geometry " << g << " pose " << i;
      EXPECT_LT(fk->residual_mm, 1e-9);
      EXPECT_EQ(fk->branch, 0);
      const ActuatorVector back = *tripod.inverse(fk->pose);
      EXPECT_LT((back - q).cwiseAbs().maxCoeff(), 1e-9);
      max_iterations = std::max(max_iterations, fk->iterations);
    }
    EXPECT_LE(max_iterations, 12) << "cold starts from home should converge quadratically";
  }
}

TEST(Tripod, JacobianMatchesFiniteDifferencesOfInverseKinematics) {
  std::mt19937_64 rng(7);
  for (AngleConvention convention : {AngleConvention::abc, AngleConvention::krylov}) {
    for (int g = 0; g < 5; ++g) {
      const RandomTripod t = random_tripod(rng, convention);
      const Tripod tripod = *Tripod::create(t.geometry, convention, t.home);
      const AxisMask mask = tripod.controlled_axes();
      for (int i = 0; i < 20; ++i) {
        const Pose pose = *tripod.complete_pose(random_controlled_pose(rng, tripod));
        const JacobianMatrix j = *tripod.jacobian(pose);
        ASSERT_EQ(j.rows(), 3);
        ASSERT_EQ(j.cols(), 3);
        const PoseVector c = vector_from_pose(convention, pose);
        int column = 0;
        for (int k = 0; k < 6; ++k) {
          if (!mask.controlled[k]) continue;
          const double h = k < 3 ? 1e-4 : 1e-7;
          PoseVector plus = c, minus = c;
          plus[k] += h;
          minus[k] -= h;
          const ActuatorVector qp = *tripod.inverse(pose_from_vector(convention, plus));
          const ActuatorVector qm = *tripod.inverse(pose_from_vector(convention, minus));
          const Eigen::Vector3d numeric = (qp - qm) / (2 * h);
          const double tolerance = k < 3 ? 1e-7 : 1e-5;  // mm/mm and mm/rad (entries are ~1 and ~100)
          EXPECT_LT((numeric - j.col(column)).norm(), tolerance) << "coordinate " << k;
          ++column;
        }
      }
    }
  }
}

TEST(Tripod, ForwardAllFindsTheTruePoseAmongConsistentAssemblies) {
  std::mt19937_64 rng(5);
  for (int g = 0; g < 5; ++g) {
    const RandomTripod t = random_tripod(rng, AngleConvention::abc);
    const Tripod tripod = *Tripod::create(t.geometry, AngleConvention::abc, t.home);
    for (int i = 0; i < 4; ++i) {
      const Pose truth = *tripod.complete_pose(random_controlled_pose(rng, tripod));
      const ActuatorVector q = *tripod.inverse(truth);
      auto all = tripod.forward_all(q);
      ASSERT_TRUE(all) << all.error().message;
      EXPECT_LE(all->size(), 16u);  // a 3-RPS tripod has at most 16 assembly modes
      bool found = false;
      for (const FkSolution& s : *all) {
        EXPECT_LT((tripod.strut_lengths(s.pose) - q.head<3>()).cwiseAbs().maxCoeff(), 1e-8);
        EXPECT_LT(tripod.plane_residuals_mm(s.pose).cwiseAbs().maxCoeff(), 1e-8);
        const PoseDistance d = pose_distance(s.pose, truth);
        found = found || (d.position_mm < 1e-7 && d.rotation_rad < 1e-9);
      }
      EXPECT_TRUE(found) << "geometry " << g << " pose " << i;
      // Every mirrored assembly is reached from a guess in its own mode.
      for (const FkSolution& s : *all) {
        auto again = tripod.forward(q, s.pose);
        ASSERT_TRUE(again) << again.error().message;
        EXPECT_LT(pose_distance(again->pose, s.pose).position_mm, 1e-7);
      }
    }
  }
}

TEST(Tripod, ForwardReportsAJumpToAnotherAssemblyMode) {
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  const auto& tripod = dynamic_cast<const Tripod&>(*machine.mechanism);
  const ActuatorVector q = *tripod.inverse(tripod.home());
  auto all = tripod.forward_all(q);
  ASSERT_TRUE(all);
  ASSERT_GE(all->size(), 2u);
  EXPECT_EQ((*all)[0].branch, 0);  // the home itself, nearest first
  EXPECT_LT(pose_distance((*all)[0].pose, tripod.home()).position_mm, 1e-7);
  // The mirror image below the base: starting there stays there, with a non-zero branch label.
  for (const FkSolution& s : *all) {
    if (s.pose.position_mm.z() < 0) {
      auto below = tripod.forward(q, s.pose);
      ASSERT_TRUE(below);
      EXPECT_NE(below->branch, 0);
    }
  }
}

TEST(Tripod, PoseInputAcceptsTheControlledCoordinatesOnly) {
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  auto pose = pose_from_user(*machine.mechanism, {780.0, 5.0, -3.0}, "--pose");
  ASSERT_TRUE(pose) << pose.error().message;
  const PoseVector c = vector_from_pose(AngleConvention::abc, *pose);
  EXPECT_NEAR(c[2], 780.0, 1e-12);
  EXPECT_NEAR(c[3], 5.0 * kDeg, 1e-12);
  EXPECT_NEAR(c[4], -3.0 * kDeg, 1e-12);
  const auto& tripod = dynamic_cast<const Tripod&>(*machine.mechanism);
  EXPECT_LT(tripod.plane_residuals_mm(*pose).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Tripod, UnreachableTiltIsReported) {
  // Axes turned 30° from the tangents: a·A ≠ 0, and at large tilts no yaw satisfies (31).
  const std::string axes =
      "base_axes:\n"
      "  - [-0.8660254037844386, -0.5, 0]\n"
      "  - [0.8660254037844386, -0.5, 0]\n"
      "  - [0, 1, 0]\n";
  const Machine machine = test::machine_from_text(tripod_yaml("abc", axes, "home: [0, 0, 800, 0, 0, 0]\n"));
  PoseVector c = PoseVector::Zero();
  c[2] = 800;
  c[3] = 80 * kDeg;
  auto q = machine.mechanism->inverse(pose_from_vector(AngleConvention::abc, c));
  ASSERT_FALSE(q);
  EXPECT_EQ(q.error().code, ErrorCode::unreachable);
  EXPECT_NE(q.error().message.find("(31)"), std::string::npos) << q.error().message;
  EXPECT_EQ(machine.mechanism->complete_pose(pose_from_vector(AngleConvention::abc, c)).error().code,
            ErrorCode::unreachable);
}

TEST(Tripod, StrutLengthsThatCannotHoldThePlatformAreUnreachable) {
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  ActuatorVector q(3);
  q << 50.0, 50.0, 50.0;  // platform joints ≈ 346 mm apart, base joints ≈ 693 mm apart
  auto fk = machine.mechanism->forward(q, machine.mechanism->home());
  ASSERT_FALSE(fk);
  EXPECT_EQ(fk.error().code, ErrorCode::unreachable);
  auto all = machine.mechanism->forward_all(q);
  ASSERT_FALSE(all);
  EXPECT_EQ(all.error().code, ErrorCode::unreachable);
  ActuatorVector two(2);
  two << 600.0, 600.0;
  EXPECT_EQ(machine.mechanism->forward(two, machine.mechanism->home()).error().code, ErrorCode::bad_input);
}

TEST(TripodFile, MissingKeyNamesFileLineAndKey) {
  std::string yaml = tripod_yaml();
  yaml = yaml.substr(0, yaml.find("base_axes:")) + yaml.substr(yaml.find("platform_joints:"));
  const std::string message = tripod_load_error(yaml, "no_axes.yaml");
  EXPECT_TRUE(std::regex_search(message, std::regex(R"(^no_axes\.yaml:[0-9]+:[0-9]+: base_axes: missing)")))
      << message;
}

TEST(TripodFile, MisspeltKeyNamesFileLineAndKey) {
  std::string yaml = tripod_yaml();
  yaml.replace(yaml.find("base_axes:"), 10, "base_axis:");
  const std::string message = tripod_load_error(yaml, "typo.yaml");
  EXPECT_NE(message.find("typo.yaml:7:1: base_axis: unknown key"), std::string::npos) << message;
}

TEST(TripodFile, WrongCountNamesFileLineAndKey) {
  const std::string two_axes = "base_axes:\n  - [-1, 0, 0]\n  - [0.5, -0.8660254037844386, 0]\n";
  const std::string message = tripod_load_error(tripod_yaml("abc", two_axes), "count.yaml");
  EXPECT_NE(message.find("count.yaml:8:3: base_axes: expected a list of 3 points"), std::string::npos)
      << message;
  const std::string short_point =
      "base_axes:\n  - [-1, 0]\n  - [0.5, -0.8660254037844386, 0]\n  - [0.5, 0.8, 0]\n";
  const std::string message2 = tripod_load_error(tripod_yaml("abc", short_point), "short.yaml");
  EXPECT_NE(message2.find("short.yaml:8:5: base_axes[0]: expected 3 numbers, got 2"), std::string::npos)
      << message2;
}

TEST(TripodFile, TiltedOrZeroOrParallelAxesAreRejected) {
  const std::string tilted =
      "base_axes:\n  - [-1, 0, 0]\n  - [0.5, -0.8660254037844386, 0.1]\n  - [0.5, 0.8, 0]\n";
  const std::string message = tripod_load_error(tripod_yaml("abc", tilted), "tilted.yaml");
  EXPECT_NE(message.find("tilted.yaml:9:5: base_axes[1]:"), std::string::npos) << message;
  EXPECT_NE(message.find("horizontal"), std::string::npos) << message;
  const std::string zero = "base_axes:\n  - [-1, 0, 0]\n  - [0.5, -0.8660254037844386, 0]\n  - [0, 0, 0]\n";
  EXPECT_TRUE(test::names_yaml_place(tripod_load_error(tripod_yaml("abc", zero), "zero.yaml"), "zero.yaml:10",
                                     "base_axes[2]:"));
  const std::string parallel = "base_axes:\n  - [1, 0, 0]\n  - [-1, 0, 0]\n  - [2, 0, 0]\n";
  EXPECT_TRUE(test::names_yaml_place(tripod_load_error(tripod_yaml("abc", parallel), "parallel.yaml"),
                                     "parallel.yaml:8", "base_axes:"));
}

TEST(TripodFile, EulerAnglesAreRejected) {
  const std::string message = tripod_load_error(tripod_yaml("euler_zxz"), "euler.yaml");
  EXPECT_NE(message.find("euler.yaml:2:9: angles:"), std::string::npos) << message;
  EXPECT_NE(message.find("abc or krylov"), std::string::npos) << message;
}

TEST(TripodFile, UnreachableHomeIsRejectedAtTheHomeLine) {
  // Axes radial: every strut plane is tangent to the 400 mm circle, which a 200 mm platform cannot reach.
  const std::string radial =
      "base_axes:\n  - [0, 1, 0]\n  - [-0.8660254037844386, -0.5, 0]\n  - [0.8660254037844386, -0.5, 0]\n";
  const std::string message =
      tripod_load_error(tripod_yaml("abc", radial, "home: [0, 0, 800, 0, 0, 0]\n"), "radial.yaml");
  EXPECT_NE(message.find("radial.yaml:15:7: home:"), std::string::npos) << message;
}

TEST(TripodFile, HomeOutsideTheActuatorRangeIsRejected) {
  const std::string message = tripod_load_error(
      tripod_yaml("abc", "", "limits: {actuator_min: 100, actuator_max: 300}\nhome: [0, 0, 800, 0, 0, 0]\n"),
      "range.yaml");
  EXPECT_NE(message.find("range.yaml:16:7: home:"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm
