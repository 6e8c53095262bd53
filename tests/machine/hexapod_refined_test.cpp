// Refined hexapod with real cardan joints (Smirnov 2019, §2.2.5, eqs. 27–28): ideal defaults reproduce the
// ideal hexapod, small joint errors change the lengths by their own order, IK∘FK round trips, the Jacobian,
// errors and the file.
#include "machine/hexapod_refined.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <string>

#include "core/units.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::kCh5HexapodGeometry;

Pose hexapod_refined_krylov_pose(double x, double y, double z, double psi_deg, double theta_deg,
                                 double gamma_deg) {
  PoseVector c;
  c << x, y, z, rad_from_deg(psi_deg), rad_from_deg(theta_deg), rad_from_deg(gamma_deg);
  return pose_from_vector(AngleConvention::krylov, c);
}

Pose hexapod_refined_random_pose(std::mt19937_64& rng, const Pose& around, double mm, double deg) {
  PoseVector c = vector_from_pose(AngleConvention::krylov, around);
  for (int k = 0; k < 3; ++k) c[k] += test::uniform(rng, -mm, mm);
  for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(test::uniform(rng, -deg, deg));
  return pose_from_vector(AngleConvention::krylov, c);
}

Eigen::Vector3d hexapod_refined_random_vector(std::mt19937_64& rng, double size) {
  return {test::uniform(rng, -size, size), test::uniform(rng, -size, size), test::uniform(rng, -size, size)};
}

// A calibrated-looking joint: offsets up to `offset_mm` per component, axes tilted up to `tilt_rad` per
// component.
CardanJoint random_joint(std::mt19937_64& rng, double offset_mm, double tilt_rad) {
  CardanJoint joint;
  joint.axis1 = (Eigen::Vector3d::UnitY() + hexapod_refined_random_vector(rng, tilt_rad)).normalized();
  joint.axis2 = (Eigen::Vector3d::UnitX() + hexapod_refined_random_vector(rng, tilt_rad)).normalized();
  joint.strut_axis = (Eigen::Vector3d::UnitZ() + hexapod_refined_random_vector(rng, tilt_rad)).normalized();
  joint.offset1_mm = hexapod_refined_random_vector(rng, offset_mm);
  joint.offset2_mm = hexapod_refined_random_vector(rng, offset_mm);
  joint.strut_offset_mm = hexapod_refined_random_vector(rng, offset_mm);
  return joint;
}

// A 6-6 or 6-3 hexapod near the ch5 one, with random cardan errors.
HexapodRefined random_refined(std::mt19937_64& rng) {
  HexapodGeometry geometry;
  const double base_radius = test::uniform(rng, 350, 450);
  const double platform_radius = test::uniform(rng, 150, 250);
  const double pair_half_deg = test::uniform(rng, 0, 15);
  for (int j = 0; j < 6; ++j) {
    const double a = rad_from_deg(60.0 * j + test::uniform(rng, -4, 4));
    geometry.base_joints_mm[j] = {base_radius * std::cos(a), base_radius * std::sin(a),
                                  test::uniform(rng, -5, 5)};
    const double b = rad_from_deg(120.0 * (j / 2) + 30.0 + (j % 2 == 0 ? -1 : 1) * pair_half_deg);
    geometry.platform_joints_mm[j] = {platform_radius * std::cos(b), platform_radius * std::sin(b), -150.0};
  }
  std::array<CardanJoint, 6> joints;
  for (auto& joint : joints) joint = random_joint(rng, 0.3, rad_from_deg(0.5));
  return HexapodRefined(geometry, joints, AngleConvention::krylov,
                        hexapod_refined_krylov_pose(0, 0, 700, 0, 0, 0));
}

TEST(HexapodRefined, IdealDefaultsGiveExactlyTheIdealHexapodLengths) {
  const Machine ideal = test::machine_from_text(std::string("type: hexapod\n") + kCh5HexapodGeometry);
  const Machine refined = test::machine_from_text(std::string("type: hexapod_refined\n") +
                                                  kCh5HexapodGeometry + "cardan: [{}, {}, {}, {}, {}, {}]\n");
  std::mt19937_64 rng(1);
  for (int i = 0; i < 1000; ++i) {
    const Pose pose = hexapod_refined_random_pose(rng, refined.mechanism->home(), 80, 10);
    const auto l_ideal = ideal.mechanism->inverse(pose);
    const auto l_refined = refined.mechanism->inverse(pose);
    ASSERT_TRUE(l_ideal.ok() && l_refined.ok());
    EXPECT_LE((*l_ideal - *l_refined).cwiseAbs().maxCoeff(), 1e-12);
  }
  // The strut lengths Smirnov 2019 prints for its test hexapod (§5.2.5).
  const auto lengths = refined.mechanism->inverse(hexapod_refined_krylov_pose(-50, 0, 700, 0, 0, 0));
  ASSERT_TRUE(lengths.ok());
  const double expected[6] = {623.7911728445, 607.5487036598, 603.1222458757,
                              586.3074649620, 588.5880863511, 621.6397151039};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR((*lengths)[j], expected[j], 1e-9) << "strut " << j + 1;
}

TEST(HexapodRefined, AxisTiltsAloneKeepTheIdealLengths) {
  // With every offset zero the strut axis passes through A on both joint axes: |B − A| = L whatever the axes.
  std::mt19937_64 rng(2);
  const Machine ideal = test::machine_from_text(std::string("type: hexapod\n") + kCh5HexapodGeometry);
  const auto& hexapod = dynamic_cast<const Hexapod&>(*ideal.mechanism);
  std::array<CardanJoint, 6> joints;
  for (auto& joint : joints) {
    joint = random_joint(rng, 0.0, rad_from_deg(1.0));
  }
  const HexapodRefined refined(hexapod.geometry(), joints, AngleConvention::krylov, hexapod.home());
  for (int i = 0; i < 200; ++i) {
    const Pose pose = hexapod_refined_random_pose(rng, hexapod.home(), 80, 10);
    const auto a = hexapod.inverse(pose);
    const auto b = refined.inverse(pose);
    ASSERT_TRUE(b.ok()) << b.error().message;
    EXPECT_LE((*a - *b).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(HexapodRefined, SmallJointErrorsChangeLengthsByTheirOwnOrder) {
  const Machine ideal = test::machine_from_text(std::string("type: hexapod\n") + kCh5HexapodGeometry);
  const auto& hexapod = dynamic_cast<const Hexapod&>(*ideal.mechanism);
  std::mt19937_64 rng(3);
  // One 0.1 mm offset at a time, in a random direction, at each of the three places of eq. 27.
  for (int place = 0; place < 3; ++place) {
    for (int i = 0; i < 100; ++i) {
      std::array<CardanJoint, 6> joints;
      const Eigen::Vector3d offset = 0.1 * hexapod_refined_random_vector(rng, 1.0).normalized();
      for (auto& joint : joints) {
        (place == 0 ? joint.offset1_mm : place == 1 ? joint.offset2_mm : joint.strut_offset_mm) = offset;
      }
      const HexapodRefined refined(hexapod.geometry(), joints, AngleConvention::krylov, hexapod.home());
      const Pose pose = hexapod_refined_random_pose(rng, hexapod.home(), 60, 8);
      const auto a = hexapod.inverse(pose);
      const auto b = refined.inverse(pose);
      ASSERT_TRUE(b.ok()) << b.error().message;
      const double change = (*a - *b).cwiseAbs().maxCoeff();
      EXPECT_GT(change, 0.0);
      EXPECT_LE(change, 0.1 + 1e-6) << "place " << place;
    }
  }
  // The example machine (0.05–0.2 mm offsets, 0.1° tilts) differs from its ideal twin by that order.
  const Machine example = test::machine_from_example("examples/machines/hexapod_refined.yaml");
  const auto& refined = dynamic_cast<const HexapodRefined&>(*example.mechanism);
  const auto a = refined.ideal().inverse(refined.home());
  const auto b = refined.inverse(refined.home());
  ASSERT_TRUE(b.ok());
  EXPECT_GT((*a - *b).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_LT((*a - *b).cwiseAbs().maxCoeff(), 0.5);
}

TEST(HexapodRefined, LegStatesSatisfyEquation28) {
  const Machine example = test::machine_from_example("examples/machines/hexapod_refined.yaml");
  const auto& refined = dynamic_cast<const HexapodRefined&>(*example.mechanism);
  std::mt19937_64 rng(4);
  for (int i = 0; i < 200; ++i) {
    const Pose pose = hexapod_refined_random_pose(rng, refined.home(), 80, 10);
    const auto states = refined.leg_states(pose);
    ASSERT_TRUE(states.ok());
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d b = pose.to_base(refined.geometry().platform_joints_mm[j]);
      const Eigen::Vector3d end =
          cardan_strut_end(refined.joints()[j], refined.geometry().base_joints_mm[j], (*states)[j]);
      EXPECT_LT((end - b).norm(), 1e-10);
      EXPECT_LT(std::abs((*states)[j].angle1_rad), kPi / 4);
      EXPECT_LT(std::abs((*states)[j].angle2_rad), kPi / 4);
    }
  }
}

TEST(HexapodRefinedProperty, InverseThenForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(20260501);
  FkOptions options;
  options.tolerance_mm = 1e-12;
  for (int g = 0; g < 5; ++g) {
    const HexapodRefined refined = random_refined(rng);
    const auto home_twist = refined.twist_jacobian(refined.home());
    ASSERT_TRUE(home_twist.ok());
    const double home_det = home_twist->determinant();
    int accepted = 0, skipped = 0;
    while (accepted < 1000) {
      const Pose truth = hexapod_refined_random_pose(rng, refined.home(), 60, 8);
      const auto twist = refined.twist_jacobian(truth);
      ASSERT_TRUE(twist.ok());
      // Skip poses across or near a singularity from home, where "the" pose is not defined (counted below).
      if (twist->determinant() * home_det <= 0 ||
          Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>>(*twist).singularValues()[5] < 0.2) {
        ++skipped;
        continue;
      }
      ++accepted;
      const auto lengths = refined.inverse(truth);
      ASSERT_TRUE(lengths.ok()) << lengths.error().message;
      const Pose guess = hexapod_refined_random_pose(rng, truth, 2, 1);
      const auto fk = refined.forward(*lengths, guess, options);
      ASSERT_TRUE(fk.ok()) << fk.error().message;
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-9);
      EXPECT_LT(d.rotation_rad, 1e-11);
      const auto back = refined.inverse(fk->pose);
      ASSERT_TRUE(back.ok());
      EXPECT_LE((*back - *lengths).cwiseAbs().maxCoeff(), 1e-9);
    }
    EXPECT_LT(skipped, 100) << "too many near-singular samples: the generator is off";
  }
}

TEST(HexapodRefined, JacobianMatchesFiniteDifferencesOfInverse) {
  std::mt19937_64 rng(6);
  for (int g = 0; g < 5; ++g) {
    const HexapodRefined refined = random_refined(rng);
    const PoseVector c =
        vector_from_pose(AngleConvention::krylov, hexapod_refined_random_pose(rng, refined.home(), 50, 8));
    const auto j = refined.jacobian(pose_from_vector(AngleConvention::krylov, c));
    ASSERT_TRUE(j.ok());
    for (int k = 0; k < 6; ++k) {
      const double h = k < 3 ? 1e-4 : 1e-6;
      PoseVector cp = c, cm = c;
      cp[k] += h;
      cm[k] -= h;
      const auto lp = refined.inverse(pose_from_vector(AngleConvention::krylov, cp));
      const auto lm = refined.inverse(pose_from_vector(AngleConvention::krylov, cm));
      ASSERT_TRUE(lp.ok() && lm.ok());
      const ActuatorVector fd = (*lp - *lm) / (2 * h);
      EXPECT_LT((fd - j->col(k)).cwiseAbs().maxCoeff(), 1e-5 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
          << "column " << k;
    }
  }
}

TEST(HexapodRefined, AllAssemblyModesContainTheTruePose) {
  const Machine example = test::machine_from_example("examples/machines/hexapod_refined.yaml");
  const Pose truth = hexapod_refined_krylov_pose(20, -30, 680, 4, -3, 6);
  const auto lengths = example.mechanism->inverse(truth);
  ASSERT_TRUE(lengths.ok());
  const auto all = example.mechanism->forward_all(*lengths);
  ASSERT_TRUE(all.ok()) << all.error().message;
  bool found = false;
  for (const auto& solution : *all) {
    const auto back = example.mechanism->inverse(solution.pose);
    if (!back) continue;  // a mode with a folded joint is not a real assembly of this machine
    EXPECT_LE((*back - *lengths).cwiseAbs().maxCoeff(), 1e-9);
    const PoseDistance d = pose_distance(solution.pose, truth);
    found = found || (d.position_mm < 1e-8 && d.rotation_rad < 1e-10);
  }
  EXPECT_TRUE(found);
}

TEST(HexapodRefined, PlatformUnderTheBaseIsUnreachable) {
  const Machine example = test::machine_from_example("examples/machines/hexapod_refined.yaml");
  const auto lengths = example.mechanism->inverse(hexapod_refined_krylov_pose(0, 0, -400, 0, 0, 0));
  ASSERT_FALSE(lengths.ok());
  EXPECT_EQ(lengths.error().code, ErrorCode::unreachable);
  EXPECT_NE(lengths.error().message.find("strut 1"), std::string::npos) << lengths.error().message;
}

std::string hexapod_refined_error_of(const std::string& yaml, const std::string& name) {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok());
  return machine.ok() ? std::string() : machine.error().message;
}

TEST(HexapodRefinedFile, ErrorsNameFileLineAndKey) {
  const std::string head = std::string("type: hexapod_refined\n") + kCh5HexapodGeometry;  // 18 lines
  // Missing `cardan`.
  std::string message = hexapod_refined_error_of(head, "refined.yaml");
  EXPECT_NE(message.find("refined.yaml:1:1: cardan: missing"), std::string::npos) << message;
  // Misspelt key inside the third joint map (line 22).
  message = hexapod_refined_error_of(
      head + "cardan:\n  - {}\n  - {}\n  - {axsi1: [0, 1, 0]}\n  - {}\n  - {}\n  - {}\n", "refined.yaml");
  EXPECT_NE(message.find("refined.yaml:22:6: cardan[2].axsi1: unknown key"), std::string::npos) << message;
  // Wrong count (line 19).
  message = hexapod_refined_error_of(head + "cardan: [{}, {}, {}, {}, {}]\n", "refined.yaml");
  EXPECT_NE(message.find("refined.yaml:19:9: cardan: expected a list of 6 joint maps, got 5"),
            std::string::npos)
      << message;
  // Wrong vector size (line 20).
  message = hexapod_refined_error_of(
      head + "cardan:\n  - {offset1: [0.1, 0.2]}\n  - {}\n  - {}\n  - {}\n  - {}\n  - {}\n", "refined.yaml");
  EXPECT_NE(message.find("refined.yaml:20:15: cardan[0].offset1: expected 3 numbers, got 2"),
            std::string::npos)
      << message;
  // Zero axis, parallel axes, offsets that are not calibration errors.
  message =
      hexapod_refined_error_of(head + "cardan: [{axis1: [0, 0, 0]}, {}, {}, {}, {}, {}]\n", "refined.yaml");
  EXPECT_NE(message.find("cardan[0].axis1: a direction must not be zero"), std::string::npos) << message;
  message =
      hexapod_refined_error_of(head + "cardan: [{}, {axis2: [0, 1, 0.1]}, {}, {}, {}, {}]\n", "refined.yaml");
  EXPECT_NE(message.find("cardan[1].axis2"), std::string::npos) << message;
  message = hexapod_refined_error_of(head + "cardan: [{}, {}, {}, {offset1: [80, 0, 0]}, {}, {}]\n",
                                     "refined.yaml");
  EXPECT_NE(message.find("cardan[3]: joint offsets add up to 80.000 mm"), std::string::npos) << message;
  // Misspelt top-level key.
  message = hexapod_refined_error_of(head + "cardans: [{}, {}, {}, {}, {}, {}]\n", "refined.yaml");
  EXPECT_NE(message.find("refined.yaml:19:1: cardans: unknown key"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm
