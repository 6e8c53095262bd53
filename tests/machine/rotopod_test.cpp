// Rotopod (Smirnov 2019, §2.2.8): the closed-form carriage angles and their branches, IK∘FK round trips, the
// Jacobian, unreachable poses, the angle window, degrees at the user boundary, and the machine file.
#include "machine/rotopod.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/units.hpp"
#include "io/pose_input.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Pose rotopod_random_pose(std::mt19937_64& rng, const Pose& around, double mm, double deg) {
  PoseVector c = vector_from_pose(AngleConvention::abc, around);
  for (int k = 0; k < 3; ++k) c[k] += test::uniform(rng, -mm, mm);
  for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(test::uniform(rng, -deg, deg));
  return pose_from_vector(AngleConvention::abc, c);
}

const Rotopod& as_rotopod(const Machine& m) {
  return dynamic_cast<const Rotopod&>(*m.mechanism);
}

Rotopod jittered(const Rotopod& example, std::mt19937_64& rng) {
  RotopodGeometry g = example.geometry();
  g.circle_center_mm += Eigen::Vector2d(test::uniform(rng, -10, 10), test::uniform(rng, -10, 10));
  g.circle_radius_mm += test::uniform(rng, -20, 20);
  for (int j = 0; j < 6; ++j) {
    g.joint_heights_mm[j] += test::uniform(rng, -10, 10);
    g.strut_lengths_mm[j] += test::uniform(rng, -15, 15);
    g.platform_joints_mm[j] += Eigen::Vector3d(test::uniform(rng, -10, 10), test::uniform(rng, -10, 10),
                                               test::uniform(rng, -10, 10));
  }
  return Rotopod(g, AngleConvention::abc, example.home());
}

TEST(Rotopod, ExampleLoadsWithAngularActuators) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  EXPECT_EQ(m.mechanism->actuator_count(), 6);
  EXPECT_TRUE(m.mechanism->actuators_are_angles());
  EXPECT_EQ(m.mechanism->controlled_axes().count(), 6);
  // Limits are degrees in the file, radians inside.
  ASSERT_TRUE(m.limits.speed.has_value());
  EXPECT_NEAR(*m.limits.speed, rad_from_deg(90), 1e-15);
}

TEST(Rotopod, CarriagesSitOnTheirStrutSpheresOnTheGivenBranch) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  const Rotopod& rotopod = as_rotopod(m);
  const RotopodGeometry& g = rotopod.geometry();
  std::mt19937_64 rng(1);
  for (int i = 0; i < 500; ++i) {
    const Pose pose = rotopod_random_pose(rng, rotopod.home(), 40, 5);
    const auto phi = rotopod.inverse(pose);
    ASSERT_TRUE(phi.ok()) << phi.error().message;
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d b = pose.to_base(g.platform_joints_mm[j]);
      const Eigen::Vector3d a = rotopod.carriage_mm(j, (*phi)[j]);
      EXPECT_NEAR((a - b).norm(), g.strut_lengths_mm[j], 1e-9);
      EXPECT_NEAR(a.x(), g.circle_center_mm.x() + g.circle_radius_mm * std::cos((*phi)[j]), 1e-12);
      // Branch +1: counter-clockwise (seen from +z) of the point of the circle nearest the platform joint.
      const double nearest = std::atan2(b.y() - g.circle_center_mm.y(), b.x() - g.circle_center_mm.x());
      EXPECT_GT(g.branches[j] * std::sin((*phi)[j] - nearest), 0.0) << "carriage " << j + 1;
      // Angles stay in the 360° window around the home angles.
      EXPECT_LE(std::abs((*phi)[j] - rotopod.reference_angles_rad()[j]), kPi);
    }
  }
}

TEST(RotopodProperty, InverseThenForwardRoundTripsOnRandomGeometries) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  std::mt19937_64 rng(20260504);
  FkOptions options;
  options.tolerance_mm = 1e-13;  // rad here: 1e-13 rad on a 300 mm circle is 3e-11 mm of carriage travel
  for (int g = 0; g < 5; ++g) {
    const Rotopod rotopod = jittered(as_rotopod(m), rng);
    ASSERT_GT(rotopod.path_conditioning(rotopod.home()), 0.2) << "generator produced a singular home";
    const double home_det = rotopod.strut_line_determinant(rotopod.home());
    int accepted = 0, skipped = 0;
    while (accepted < 1000) {
      const Pose truth = rotopod_random_pose(rng, rotopod.home(), 40, 5);
      // Near a singularity "the" pose is not defined: skip (and count) poses near one or across one from
      // home.
      const double det = rotopod.strut_line_determinant(truth);
      if (rotopod.path_conditioning(truth) < 0.1 || det * home_det <= 0 ||
          std::abs(det) < 0.2 * std::abs(home_det)) {
        ++skipped;
        continue;
      }
      ++accepted;
      const auto phi = rotopod.inverse(truth);
      ASSERT_TRUE(phi.ok()) << phi.error().message;
      const auto fk = rotopod.forward(*phi, rotopod_random_pose(rng, truth, 1, 0.5), options);
      ASSERT_TRUE(fk.ok()) << fk.error().message;
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-9);
      EXPECT_LT(d.rotation_rad, 1e-11);
      const auto back = rotopod.inverse(fk->pose);
      ASSERT_TRUE(back.ok());
      EXPECT_LE((*back - *phi).cwiseAbs().maxCoeff(), 1e-12);  // rad
    }
    EXPECT_LT(skipped, 200) << "too many near-singular samples: the generator is off";
  }
}

TEST(Rotopod, ForwardAcceptsAnglesOfAnyTurn) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  const Pose truth = test::abc_pose(15, -10, 330, 2, -3, 8);
  auto phi = m.mechanism->inverse(truth);
  ASSERT_TRUE(phi.ok());
  ActuatorVector turned = *phi;
  turned[0] += 2 * kPi;
  turned[3] -= 4 * kPi;
  const auto fk = m.mechanism->forward(turned, m.mechanism->home());
  ASSERT_TRUE(fk.ok()) << fk.error().message;
  EXPECT_LT(pose_distance(fk->pose, truth).position_mm, 1e-8);
}

TEST(Rotopod, JacobianMatchesFiniteDifferencesOfInverse) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  std::mt19937_64 rng(7);
  for (int g = 0; g < 5; ++g) {
    const Rotopod rotopod = jittered(as_rotopod(m), rng);
    const PoseVector c =
        vector_from_pose(AngleConvention::abc, rotopod_random_pose(rng, rotopod.home(), 30, 4));
    const auto j = rotopod.jacobian(pose_from_vector(AngleConvention::abc, c));
    ASSERT_TRUE(j.ok()) << j.error().message;
    for (int k = 0; k < 6; ++k) {
      const double h = k < 3 ? 1e-4 : 1e-6;
      PoseVector cp = c, cm = c;
      cp[k] += h;
      cm[k] -= h;
      const auto p = rotopod.inverse(pose_from_vector(AngleConvention::abc, cp));
      const auto q = rotopod.inverse(pose_from_vector(AngleConvention::abc, cm));
      ASSERT_TRUE(p.ok() && q.ok());
      const ActuatorVector fd = (*p - *q) / (2 * h);
      EXPECT_LT((fd - j->col(k)).cwiseAbs().maxCoeff(), 1e-5 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
          << "column " << k;
    }
  }
}

TEST(Rotopod, StrutsThatCannotReachTheCircleAreUnreachable) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  const auto high = m.mechanism->inverse(test::abc_pose(0, 0, 900, 0, 0, 0));
  ASSERT_FALSE(high.ok());
  EXPECT_EQ(high.error().code, ErrorCode::unreachable);
  EXPECT_NE(high.error().message.find("carriage 1"), std::string::npos) << high.error().message;
  EXPECT_NE(high.error().message.find("mm too short"), std::string::npos) << high.error().message;
  // Platform joints near the axis, level with the carriages: the struts are longer than the farthest point.
  RotopodGeometry g = as_rotopod(m).geometry();
  for (auto& b : g.platform_joints_mm) b *= 0.1;
  const Rotopod small(g, AngleConvention::abc, test::abc_pose(0, 0, 300, 0, 0, 0));
  const auto low = small.inverse(test::abc_pose(0, 0, -100, 0, 0, 0));
  ASSERT_FALSE(low.ok());
  EXPECT_EQ(low.error().code, ErrorCode::unreachable);
  EXPECT_NE(low.error().message.find("mm too long"), std::string::npos) << low.error().message;
  const auto j = m.mechanism->jacobian(test::abc_pose(0, 0, 900, 0, 0, 0));
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error().code, ErrorCode::unreachable);
}

TEST(Rotopod, UsersSeeDegrees) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  const auto phi = m.mechanism->inverse(m.mechanism->home());
  ASSERT_TRUE(phi.ok());
  const std::vector<double> shown = user_from_actuators(*m.mechanism, *phi);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(shown[j], deg_from_rad((*phi)[j]), 1e-12);
  const auto back = actuators_from_user(*m.mechanism, shown, "--actuators");
  ASSERT_TRUE(back.ok());
  EXPECT_LE((*back - *phi).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(RotopodFile, DefaultHomeIsAQuarterTurnFromTheNearestPoint) {
  // Without `home:` the tool is over the circle centre at the height where the arccos argument averages 0.
  std::string yaml = R"(type: rotopod
angles: abc
circle: {center: [10, -20], radius: 300}
joint_heights: [0, 0, 5, 5, -5, -5]
strut_lengths: [400, 400, 400, 400, 400, 400]
platform_joints:
  - [-26.04722665, 147.721162952, 0]
  - [26.04722665, 147.721162952, 0]
  - [-114.906666468, -96.418141453, 0]
  - [-140.953893118, -51.303021499, 0]
  - [140.953893118, -51.303021499, 0]
  - [114.906666468, -96.418141453, 0]
branch: [1, -1, 1, -1, 1, -1]
)";
  const Machine m = test::machine_from_text(yaml);
  const Rotopod& rotopod = as_rotopod(m);
  EXPECT_FALSE(m.home_given);
  EXPECT_NEAR(rotopod.home().position_mm.x(), 10, 1e-12);
  EXPECT_NEAR(rotopod.home().position_mm.y(), -20, 1e-12);
  EXPECT_GT(rotopod.path_conditioning(rotopod.home()), 0.3);
  const auto phi = rotopod.inverse(rotopod.home());
  ASSERT_TRUE(phi.ok());
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d b = rotopod.home().to_base(rotopod.geometry().platform_joints_mm[j]);
    const double nearest = std::atan2(b.y() + 20, b.x() - 10);
    EXPECT_NEAR(std::abs(std::remainder((*phi)[j] - nearest, 2 * kPi)), kPi / 2, 0.05)
        << "carriage " << j + 1;
  }
}

std::string rotopod_error_of(const std::string& yaml, const std::string& name) {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok());
  return machine.ok() ? std::string() : machine.error().message;
}

TEST(RotopodFile, ErrorsNameFileLineAndKey) {
  const std::string head = "type: rotopod\nangles: abc\n";  // lines 1-2
  const std::string circle = "circle: {center: [0, 0], radius: 300}\n";
  const std::string rest =
      "strut_lengths: [400, 400, 400, 400, 400, 400]\n"
      "platform_joints: [[-26, 147, 0], [26, 147, 0], [-114, -96, 0], [-140, -51, 0], [140, -51, 0], "
      "[114, -96, 0]]\n";
  // Missing circle.
  std::string message = rotopod_error_of(head + "joint_heights: 0\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:1:1: circle: missing"), std::string::npos) << message;
  // Misspelt key inside the circle (line 3).
  message =
      rotopod_error_of(head + "circle: {center: [0, 0], radus: 300}\njoint_heights: 0\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:3:26: circle.radus: unknown key"), std::string::npos) << message;
  // Missing radius.
  message = rotopod_error_of(head + "circle: {center: [0, 0]}\njoint_heights: 0\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:3:9: circle.radius: missing"), std::string::npos) << message;
  // Wrong count of heights (line 4).
  message = rotopod_error_of(head + circle + "joint_heights: [0, 0, 0, 0, 0]\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:4:16: joint_heights: expected a list of 6 numbers, got 5"),
            std::string::npos)
      << message;
  // Misspelt top-level key (line 4).
  message = rotopod_error_of(head + circle + "joint_height: 0\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:4:1: joint_height: unknown key"), std::string::npos) << message;
  // Bad branch value (line 7) and non-positive radius (line 3).
  message = rotopod_error_of(head + circle + "joint_heights: 0\n" + rest + "branch: [1, -1, 1, -1, 0, -1]\n",
                             "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:7:24: branch[4]: expected +1 or -1, got 0"), std::string::npos)
      << message;
  message =
      rotopod_error_of(head + "circle: {center: [0, 0], radius: -3}\njoint_heights: 0\n" + rest, "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:3:34: circle.radius: the circle radius must be positive"),
            std::string::npos)
      << message;
  // A home the struts cannot reach (line 7).
  message = rotopod_error_of(head + circle + "joint_heights: 0\n" + rest + "home: [0, 0, 2000, 0, 0, 0]\n",
                             "roto.yaml");
  EXPECT_NE(message.find("roto.yaml:7:7: home: the home pose is not reachable"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace pkm
