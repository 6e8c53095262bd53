// Tricept: the cardan orientation (34)–(36), IK against the explicit form (38), the tool point as pose
// origin, IK/FK round trips on random geometries, the Jacobian against finite differences, and machine-file
// validation.
#include "machine/tricept.hpp"

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

std::string tricept_yaml(const std::string& extra = "", const std::string& platform_key = "platform_joints") {
  return "type: tricept\n"
         "angles: abc\n"
         "base_joints:\n"
         "  - [0, 450, 0]\n"
         "  - [-389.7114317029974, -225, 0]\n"
         "  - [389.7114317029974, -225, 0]\n" +
         platform_key +
         ":\n"
         "  - [0, 200, 0]\n"
         "  - [-173.20508075688772, -100, 0]\n"
         "  - [173.20508075688772, -100, 0]\n" +
         extra;
}

/// 1/|M⁻¹|_F: within a factor √3 of the smallest singular value (a conditioning test without an SVD).
double tricept_smallest_singular_value(const Eigen::Matrix3d& m) {
  return std::abs(m.determinant()) > 0.0 ? 1.0 / m.inverse().norm() : 0.0;
}

std::string tricept_load_error(const std::string& yaml, const std::string& name = "bad_tricept.yaml") {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok()) << "expected " << name << " to be rejected";
  return machine ? std::string() : machine.error().message;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.position_mm = Eigen::Vector3d(x, y, z);
  return p;
}

struct RandomTricept {
  TriceptGeometry geometry;
  Eigen::Vector3d home;
};

/// Base joints near 90°, 210°, 330° on a random circle, flange joints on a smaller one, random O and tool
/// offset; rejected until the home is well away from singularities.
RandomTricept random_tricept(std::mt19937_64& rng) {
  for (;;) {
    RandomTricept t;
    const double base_radius = test::uniform(rng, 350, 550), flange_radius = test::uniform(rng, 120, 260);
    for (int j = 0; j < 3; ++j) {
      const double a = rad_from_deg(90.0 + 120.0 * j + test::uniform(rng, -12, 12));
      const double b = rad_from_deg(90.0 + 120.0 * j + test::uniform(rng, -12, 12));
      t.geometry.base_joints_mm[j] =
          Eigen::Vector3d(base_radius * std::cos(a), base_radius * std::sin(a), test::uniform(rng, -30, 30));
      t.geometry.platform_joints_mm[j] = Eigen::Vector3d(
          flange_radius * std::cos(b), flange_radius * std::sin(b), test::uniform(rng, -20, 20));
    }
    t.geometry.center_joint_mm = Eigen::Vector3d(test::uniform(rng, -30, 30), test::uniform(rng, -30, 30),
                                                 test::uniform(rng, -30, 30));
    t.geometry.tool_offset_mm = test::uniform(rng, -100, 300);
    t.home = t.geometry.center_joint_mm +
             Eigen::Vector3d(0, 0, test::uniform(rng, 1.4, 2.0) * base_radius + t.geometry.tool_offset_mm);
    auto tricept = Tricept::create(t.geometry, AngleConvention::abc, t.home);
    if (!tricept) continue;
    const Eigen::Matrix3d j = *tricept->jacobian(tricept->home());
    if (tricept_smallest_singular_value(j) < 0.05) continue;
    return t;
  }
}

/// Random tool point: C within a cone of 25° about the vertical through O, |OC| ± 150 mm around home.
Eigen::Vector3d random_tool_point(std::mt19937_64& rng, const Tricept& tricept) {
  const auto& g = tricept.geometry();
  const double home_rho = (tricept.home().position_mm - g.center_joint_mm).norm() - g.tool_offset_mm;
  const double rho = home_rho + test::uniform(rng, -150, 150);
  const double tilt = rad_from_deg(test::uniform(rng, 0, 25)), azimuth = test::uniform(rng, -kPi, kPi);
  const Eigen::Vector3d e(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth),
                          std::cos(tilt));
  return g.center_joint_mm + (rho + g.tool_offset_mm) * e;
}

TEST(Tricept, FlangeOrientationIsTheCardanOfEquations34To36) {
  TriceptGeometry g;
  g.base_joints_mm = {Eigen::Vector3d(0, 450, 0), Eigen::Vector3d(-390, -225, 0),
                      Eigen::Vector3d(390, -225, 0)};
  g.platform_joints_mm = {Eigen::Vector3d(0, 200, 0), Eigen::Vector3d(-173, -100, 0),
                          Eigen::Vector3d(173, -100, 0)};
  const Tricept tricept = *Tricept::create(g, AngleConvention::abc, Eigen::Vector3d(0, 0, 800));
  std::mt19937_64 rng(34);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d c(test::uniform(rng, -300, 300), test::uniform(rng, -300, 300),
                            test::uniform(rng, 400, 1000));
    const Pose pose = *tricept.complete_pose(at(c.x(), c.y(), c.z()));
    // (34) tan α = −y/z, (35) tan β = x/√(y² + z²); B = Rx(α)·Ry(β) (36).
    const double alpha = std::atan(-c.y() / c.z());
    const double beta = std::atan(c.x() / std::hypot(c.y(), c.z()));
    EXPECT_LT((pose.rotation - rot_x(alpha) * rot_y(beta)).norm(), 1e-14);
    // (36) entries as printed: l1 = cos β, l2 = 0, l3 = sin β, …, n3 = cos α cos β (layout = Bᵀ).
    EXPECT_NEAR(pose.rotation(0, 0), std::cos(beta), 1e-14);
    EXPECT_NEAR(pose.rotation(1, 0), std::sin(alpha) * std::sin(beta), 1e-14);
    EXPECT_NEAR(pose.rotation(2, 1), std::sin(alpha), 1e-14);
    // The flange axis points from O to C (Smirnov 2019, §2.2.7, verified), and there is no rotation about it.
    EXPECT_LT((pose.rotation.col(2) - c.normalized()).norm(), 1e-14);
    EXPECT_NEAR(pose.rotation(0, 1), 0.0, 1e-15);  // l2 = 0 in (36)
  }
}

TEST(Tricept, InverseKinematicsEqualsTheExplicitEquation38) {
  TriceptGeometry g;
  g.base_joints_mm = {Eigen::Vector3d(10, 450, 5), Eigen::Vector3d(-390, -225, -8),
                      Eigen::Vector3d(390, -215, 0)};
  g.platform_joints_mm = {Eigen::Vector3d(0, 200, 12), Eigen::Vector3d(-173, -100, 0),
                          Eigen::Vector3d(160, -110, -9)};
  const Tricept tricept = *Tricept::create(g, AngleConvention::krylov, Eigen::Vector3d(0, 0, 800));
  std::mt19937_64 rng(38);
  for (int i = 0; i < 500; ++i) {
    const double x = test::uniform(rng, -300, 300), y = test::uniform(rng, -300, 300),
                 z = test::uniform(rng, 400, 1000);
    const double rho = std::sqrt(x * x + y * y + z * z), yz = std::sqrt(y * y + z * z);
    const ActuatorVector q = *tricept.inverse(at(x, y, z));
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d& a = g.base_joints_mm[j];
      const Eigen::Vector3d& b = g.platform_joints_mm[j];
      const double l_sq = (a.x() - x) * (a.x() - x) + (a.y() - y) * (a.y() - y) + (a.z() - z) * (a.z() - z) +
                          b.squaredNorm() + 2 * (b.x() * yz / rho + b.z() * x / rho) * (x - a.x()) +
                          2 * (-b.x() * y / yz * x / rho + b.y() * z / yz + b.z() * y / rho) * (y - a.y()) +
                          2 * (-b.x() * z / yz * x / rho - b.y() * y / yz + b.z() * z / rho) * (z - a.z());
      EXPECT_NEAR(q[j], std::sqrt(l_sq), 1e-9) << "strut " << j + 1;
    }
  }
}

TEST(Tricept, PoseOriginIsTheToolPointOnTheAxis) {
  const Machine with_tool = test::machine_from_example("examples/machines/tricept.yaml");
  const Machine without_tool = test::machine_from_text(tricept_yaml("home: [0, 0, 800, 0, 0, 0]\n"));
  std::mt19937_64 rng(250);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(test::uniform(rng, -250, 250), test::uniform(rng, -250, 250),
                            test::uniform(rng, 800, 1200));
    const Eigen::Vector3d c =
        p - 250.0 * p.normalized();  // the tool is 250 mm beyond C on the axis through O
    const ActuatorVector q_tool = *with_tool.mechanism->inverse(at(p.x(), p.y(), p.z()));
    const ActuatorVector q_c = *without_tool.mechanism->inverse(at(c.x(), c.y(), c.z()));
    EXPECT_LT((q_tool - q_c).cwiseAbs().maxCoeff(), 1e-9);
    const Pose completed = *with_tool.mechanism->complete_pose(at(p.x(), p.y(), p.z()));
    EXPECT_LT((completed.position_mm - p).norm(), 1e-12);
  }
  EXPECT_EQ(with_tool.mechanism->controlled_axes().count(), 3);
  EXPECT_EQ(controlled_coordinate_names(*with_tool.mechanism), (std::vector<std::string>{"x", "y", "z"}));
}

TEST(Tricept, InverseForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(1997);
  FkOptions options;
  options.tolerance_mm = 1e-11;
  for (int g = 0; g < 5; ++g) {
    const RandomTricept t = random_tricept(rng);
    const Tricept tricept = *Tricept::create(t.geometry, AngleConvention::krylov, t.home);
    int max_iterations = 0;
    for (int i = 0; i < 1000; ++i) {
      const Eigen::Vector3d p = random_tool_point(rng, tricept);
      const Pose truth = *tricept.complete_pose(at(p.x(), p.y(), p.z()));
      const ActuatorVector q = *tricept.inverse(truth);
      auto fk = tricept.forward(q, tricept.home(), options);
      ASSERT_TRUE(fk) << "geometry " << g << " pose " << i << ": " << fk.error().message;
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-9) << "geometry " << g << " pose " << i;
      EXPECT_LT(d.rotation_rad, 1e-11);
      EXPECT_LT(fk->residual_mm, 1e-9);
      EXPECT_EQ(fk->branch, 0);
      EXPECT_LT((*tricept.inverse(fk->pose) - q).cwiseAbs().maxCoeff(), 1e-9);
      max_iterations = std::max(max_iterations, fk->iterations);
    }
    EXPECT_LE(max_iterations, 12);
  }
}

TEST(Tricept, JacobianMatchesFiniteDifferencesOfInverseKinematics) {
  std::mt19937_64 rng(3);
  for (int g = 0; g < 5; ++g) {
    const RandomTricept t = random_tricept(rng);
    const Tricept tricept = *Tricept::create(t.geometry, AngleConvention::abc, t.home);
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d p = random_tool_point(rng, tricept);
      const JacobianMatrix j = *tricept.jacobian(at(p.x(), p.y(), p.z()));
      ASSERT_EQ(j.rows(), 3);
      ASSERT_EQ(j.cols(), 3);
      for (int k = 0; k < 3; ++k) {
        const double h = 1e-4;
        Eigen::Vector3d plus = p, minus = p;
        plus[k] += h;
        minus[k] -= h;
        const Eigen::Vector3d numeric = (*tricept.inverse(at(plus.x(), plus.y(), plus.z())) -
                                         *tricept.inverse(at(minus.x(), minus.y(), minus.z()))) /
                                        (2 * h);
        EXPECT_LT((numeric - j.col(k)).norm(), 1e-7) << "column " << k;
      }
    }
  }
}

TEST(Tricept, UnreachableToolPointsAreReported) {
  const Machine machine = test::machine_from_example("examples/machines/tricept.yaml");
  for (const Pose& p : {at(0, 0, -100), at(500, 0, 0), at(0, 0, 0), at(0, 0, 200)}) {
    // below O, axis horizontal, on O, and closer to O than the 250 mm tool offset (|OC| < 0)
    auto q = machine.mechanism->inverse(p);
    ASSERT_FALSE(q);
    EXPECT_EQ(q.error().code, ErrorCode::unreachable) << q.error().message;
    EXPECT_EQ(machine.mechanism->complete_pose(p).error().code, ErrorCode::unreachable);
  }
  ActuatorVector three(3);
  three << -1.0, 800.0, 800.0;
  EXPECT_EQ(machine.mechanism->forward(three, machine.mechanism->home()).error().code, ErrorCode::bad_input);
  // Lengths no tool point can produce: the solver stops without meeting the tolerance.
  three << 10.0, 2000.0, 10.0;
  auto fk = machine.mechanism->forward(three, machine.mechanism->home());
  ASSERT_FALSE(fk);
  EXPECT_TRUE(fk.error().code == ErrorCode::not_converged || fk.error().code == ErrorCode::singular)
      << fk.error().message;
}

TEST(Tricept, PoseInputAcceptsThreeOrSixNumbers) {
  const Machine machine = test::machine_from_example("examples/machines/tricept.yaml");
  auto three = pose_from_user(*machine.mechanism, {50.0, -20.0, 1000.0}, "--pose");
  ASSERT_TRUE(three) << three.error().message;
  auto six = pose_from_user(*machine.mechanism, {50.0, -20.0, 1000.0, 30.0, 0.0, 0.0}, "--pose");
  ASSERT_TRUE(six);
  EXPECT_LT(pose_distance(*three, *six).rotation_rad, 1e-15);  // the given angles are recomputed
  EXPECT_LT((three->rotation.col(2) - Eigen::Vector3d(50, -20, 1000).normalized()).norm(), 1e-14);
}

TEST(TriceptFile, ExampleLoads) {
  const Machine machine = test::machine_from_example("examples/machines/tricept.yaml");
  ASSERT_EQ(machine.mechanism->type(), MechanismType::tricept);
  const ActuatorVector q = *machine.mechanism->inverse(machine.mechanism->home());
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(q[j], std::hypot(250.0, 800.0), 1e-9);
}

TEST(TriceptFile, DefaultHomeIsAboveTheCentreJoint) {
  const Machine machine = test::machine_from_text(
      tricept_yaml("center_joint: [20, -10, 5]\nlimits: {actuator_min: 600, actuator_max: 1000}\n"));
  const Pose& home = machine.mechanism->home();
  EXPECT_NEAR(home.position_mm.x(), 20.0, 1e-12);
  EXPECT_NEAR(home.position_mm.y(), -10.0, 1e-12);
  EXPECT_LT((home.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(TriceptFile, MissingKeyNamesFileLineAndKey) {
  std::string yaml = tricept_yaml();
  yaml = yaml.substr(0, yaml.find("platform_joints:"));
  const std::string message = tricept_load_error(yaml, "no_flange.yaml");
  EXPECT_TRUE(
      std::regex_search(message, std::regex(R"(^no_flange\.yaml:[0-9]+:[0-9]+: platform_joints: missing)")))
      << message;
}

TEST(TriceptFile, MisspeltKeyNamesFileLineAndKey) {
  const std::string message = tricept_load_error(tricept_yaml("centre_joint: [0, 0, 0]\n"), "typo.yaml");
  EXPECT_NE(message.find("typo.yaml:11:1: centre_joint: unknown key"), std::string::npos) << message;
  const std::string message2 = tricept_load_error(tricept_yaml("", "platform_joint"), "typo2.yaml");
  EXPECT_NE(message2.find("typo2.yaml:7:1: platform_joint: unknown key"), std::string::npos) << message2;
}

TEST(TriceptFile, WrongCountNamesFileLineAndKey) {
  std::string yaml = tricept_yaml();
  yaml.erase(yaml.find("  - [173.20508075688772, -100, 0]\n"));
  const std::string message = tricept_load_error(yaml, "count.yaml");
  EXPECT_NE(message.find("count.yaml:8:3: platform_joints: expected a list of 3 points"), std::string::npos)
      << message;
  const std::string message2 = tricept_load_error(tricept_yaml("center_joint: [0, 0]\n"), "centre.yaml");
  EXPECT_NE(message2.find("centre.yaml:11:15: center_joint: expected 3 numbers, got 2"), std::string::npos)
      << message2;
}

TEST(TriceptFile, ToolOffTheAxisIsRejected) {
  const std::string message = tricept_load_error(tricept_yaml("tool: [10, 0, 200]\n"), "tool.yaml");
  EXPECT_NE(message.find("tool.yaml:11:7: tool:"), std::string::npos) << message;
  EXPECT_NE(message.find("manipulator axis"), std::string::npos) << message;
}

TEST(TriceptFile, UnreachableHomeIsRejectedAtTheHomeLine) {
  const std::string message = tricept_load_error(tricept_yaml("home: [0, 0, -500, 0, 0, 0]\n"), "home.yaml");
  EXPECT_NE(message.find("home.yaml:11:7: home:"), std::string::npos) << message;
  EXPECT_NE(message.find("out of reach"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm
