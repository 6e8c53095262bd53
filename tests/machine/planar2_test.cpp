// Planar 2-DOF mechanism (Smirnov 2019, §2.1.1) against independently derived reference values and property
// tests.
#include "machine/planar2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "test_support.hpp"

namespace pkm {
namespace {

Pose point_pose(double x_mm, double y_mm) {
  Pose pose;
  pose.position_mm << x_mm, y_mm, 0.0;
  return pose;
}

ActuatorVector lengths_of(double l1_mm, double l2_mm) {
  ActuatorVector q(2);
  q << l1_mm, l2_mm;
  return q;
}

std::string planar2_yaml(const std::string& a1, const std::string& a2, const std::string& extra = "") {
  return "type: planar2\nbase_joints:\n  - " + a1 + "\n  - " + a2 + "\n" + extra;
}

/// The message of a machine file that must fail to load.
std::string planar2_load_error(const std::string& yaml, const std::string& name = "bad.yaml") {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok()) << "expected " << name << " to be rejected";
  return machine ? std::string() : machine.error().message;
}

TEST(Planar2Reference, Section61aStrutLengths) {
  const Machine m = test::machine_from_example("examples/machines/planar2.yaml");
  const auto lengths = m.mechanism->inverse(point_pose(120, 250));
  ASSERT_TRUE(lengths.ok());
  EXPECT_NEAR((*lengths)[0], 277.308492, 1e-6);
  EXPECT_NEAR((*lengths)[1], 276.586334, 1e-6);
}

TEST(Planar2Reference, Section61aBothForwardSolutionsHomeSideFirst) {
  const Machine m = test::machine_from_example("examples/machines/planar2.yaml");
  const ActuatorVector q = *m.mechanism->inverse(point_pose(120, 250));
  const auto all = m.mechanism->forward_all(q);
  ASSERT_TRUE(all.ok()) << all.error().message;
  ASSERT_EQ(all->size(), 2u);
  EXPECT_NEAR((*all)[0].pose.position_mm.x(), 120.0, 1e-6);
  EXPECT_NEAR((*all)[0].pose.position_mm.y(), 250.0, 1e-6);
  EXPECT_EQ((*all)[0].branch, 0);
  EXPECT_NEAR((*all)[1].pose.position_mm.x(), 181.310044, 1e-6);
  EXPECT_NEAR((*all)[1].pose.position_mm.y(), -209.825328, 1e-6);
  EXPECT_EQ((*all)[1].branch, 1);
  // The two other candidates of eq. (5)/(6), (−120, 250) and (−181.31, −209.83), do not satisfy eq. (3).
  EXPECT_GT(std::abs((*m.mechanism->inverse(point_pose(-120, 250)))[1] - q[1]), 1.0);
  EXPECT_GT(std::abs((*m.mechanism->inverse(point_pose(-181.310044, -209.825328)))[1] - q[1]), 1.0);

  // A warm start takes the guess's side of line A1A2.
  const auto above = m.mechanism->forward(q, point_pose(100, 200));
  ASSERT_TRUE(above.ok());
  EXPECT_NEAR(above->pose.position_mm.y(), 250.0, 1e-6);
  const auto below = m.mechanism->forward(q, point_pose(150, -150));
  ASSERT_TRUE(below.ok());
  EXPECT_NEAR(below->pose.position_mm.x(), 181.310044, 1e-6);
  EXPECT_EQ(below->branch, 1);
}

TEST(Planar2Reference, Section61aVelocityWithCorrectedEquation4) {
  const Machine m = test::machine_from_example("examples/machines/planar2.yaml");
  const auto j = m.mechanism->jacobian(point_pose(120, 250));
  ASSERT_TRUE(j.ok());
  const Eigen::Vector2d rates = *j * Eigen::Vector2d(3, -2);
  EXPECT_NEAR(rates[0], -0.504853, 1e-6);
  EXPECT_NEAR(rates[1], -3.470887, 1e-6);
  // FK velocity (eq. 7 corrected) is the inverse map: it must give back (3, −2), not the printed (−3, −2).
  const Eigen::Vector2d back = Eigen::Matrix2d(*j).inverse() * rates;
  EXPECT_NEAR(back[0], 3.0, 1e-12);
  EXPECT_NEAR(back[1], -2.0, 1e-12);
}

/// Random base joints at least 50 mm apart.
Planar2Geometry planar2_random_geometry(std::mt19937_64& rng) {
  Planar2Geometry g;
  do {
    for (auto& a : g.base_joints_mm) a = {test::uniform(rng, -500, 500), test::uniform(rng, -500, 500)};
  } while ((g.base_joints_mm[1] - g.base_joints_mm[0]).norm() < 50.0);
  return g;
}

TEST(Planar2Property, InverseThenForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(20240611);
  for (int geometry_index = 0; geometry_index < 5; ++geometry_index) {
    const Planar2Geometry g = planar2_random_geometry(rng);
    const Eigen::Vector2d mid = 0.5 * (g.base_joints_mm[0] + g.base_joints_mm[1]);
    const Eigen::Vector2d along = (g.base_joints_mm[1] - g.base_joints_mm[0]).normalized();
    const Planar2 mechanism(g, mid + 300.0 * Eigen::Vector2d(-along.y(), along.x()));
    int tested = 0;
    while (tested < 1000) {
      const Eigen::Vector2d b(test::uniform(rng, -800, 800), test::uniform(rng, -800, 800));
      // Keep away from the singular line (sin of the strut angle ≥ 0.05) and from the base joints.
      if (std::abs(mechanism.jacobian_determinant(b)) < 0.05) continue;
      if ((b - g.base_joints_mm[0]).norm() < 5.0 || (b - g.base_joints_mm[1]).norm() < 5.0) continue;
      ++tested;
      const Pose truth = point_pose(b.x(), b.y());
      const ActuatorVector q = *mechanism.inverse(truth);
      const Pose guess = point_pose(b.x() + test::uniform(rng, -1, 1), b.y() + test::uniform(rng, -1, 1));
      const auto fk = mechanism.forward(q, guess);
      ASSERT_TRUE(fk.ok()) << fk.error().message;
      EXPECT_LE(fk->residual_mm, 1e-9);
      EXPECT_LE(((*mechanism.inverse(fk->pose)) - q).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LT((fk->pose.position_mm - truth.position_mm).norm(), 1e-8);

      const auto all = mechanism.forward_all(q);
      ASSERT_TRUE(all.ok()) << all.error().message;
      ASSERT_LE(all->size(), 6u);
      bool found = false;
      for (const auto& s : *all) {
        EXPECT_LE(((*mechanism.inverse(s.pose)) - q).cwiseAbs().maxCoeff(), 1e-9);
        found = found || (s.pose.position_mm - truth.position_mm).norm() < 1e-8;
      }
      EXPECT_TRUE(found) << "forward_all misses B = (" << b.x() << ", " << b.y() << ")";
    }
  }
}

TEST(Planar2Property, JacobianMatchesCentralFiniteDifferences) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 200; ++i) {
    const Planar2Geometry g = planar2_random_geometry(rng);
    const Planar2 mechanism(g, Eigen::Vector2d(0, 1000));
    const Eigen::Vector2d b(test::uniform(rng, -800, 800), test::uniform(rng, -800, 800));
    if ((b - g.base_joints_mm[0]).norm() < 20.0 || (b - g.base_joints_mm[1]).norm() < 20.0) continue;
    const auto j = mechanism.jacobian(point_pose(b.x(), b.y()));
    ASSERT_TRUE(j.ok());
    const double h_mm = 1e-4;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d plus = b, minus = b;
      plus[k] += h_mm;
      minus[k] -= h_mm;
      const ActuatorVector dq = (*mechanism.inverse(point_pose(plus.x(), plus.y())) -
                                 *mechanism.inverse(point_pose(minus.x(), minus.y()))) /
                                (2 * h_mm);
      for (int row = 0; row < 2; ++row) EXPECT_NEAR((*j)(row, k), dq[row], 1e-7);
    }
  }
}

TEST(Planar2Errors, UnreachableLengthsNameTheLengths) {
  const Machine m = test::machine_from_example("examples/machines/planar2.yaml");
  // |A1A2| = 302.654919 mm.
  const auto too_short = m.mechanism->forward(lengths_of(100, 150), m.mechanism->home());
  ASSERT_FALSE(too_short.ok());
  EXPECT_EQ(too_short.error().code, ErrorCode::unreachable);
  EXPECT_NE(too_short.error().message.find("L1 = 100.000000 mm"), std::string::npos)
      << too_short.error().message;
  EXPECT_NE(too_short.error().message.find("L2 = 150.000000 mm"), std::string::npos)
      << too_short.error().message;

  const auto too_different = m.mechanism->forward_all(lengths_of(100, 500));
  ASSERT_FALSE(too_different.ok());
  EXPECT_EQ(too_different.error().code, ErrorCode::unreachable);

  const auto negative = m.mechanism->forward(lengths_of(-5, 300), m.mechanism->home());
  ASSERT_FALSE(negative.ok());
  EXPECT_EQ(negative.error().code, ErrorCode::unreachable);

  const auto wrong_count = m.mechanism->forward(ActuatorVector::Constant(3, 200.0), m.mechanism->home());
  ASSERT_FALSE(wrong_count.ok());
  EXPECT_EQ(wrong_count.error().code, ErrorCode::bad_input);
}

TEST(Planar2Errors, BOnTheBaseLineIsSingular) {
  const Planar2 mechanism({{Eigen::Vector2d(0, 0), Eigen::Vector2d(300, 0)}}, Eigen::Vector2d(150, 100));
  for (const ActuatorVector& q : {lengths_of(100, 200), lengths_of(400, 100)}) {
    const auto fk = mechanism.forward(q, mechanism.home());
    ASSERT_FALSE(fk.ok());
    EXPECT_EQ(fk.error().code, ErrorCode::singular) << fk.error().message;
    const auto all = mechanism.forward_all(q);
    ASSERT_FALSE(all.ok());
    EXPECT_EQ(all.error().code, ErrorCode::singular);
  }
  EXPECT_EQ(mechanism.jacobian_determinant(Eigen::Vector2d(100, 0)), 0.0);
}

TEST(Planar2MachineFile, DefaultHomeIsOnThePositiveSideAndNotSingular) {
  const Machine m = test::machine_from_text(planar2_yaml("[0, 0]", "[300, 0]"));
  EXPECT_FALSE(m.home_given);
  EXPECT_NEAR(m.mechanism->home().position_mm.x(), 150.0, 1e-9);
  EXPECT_GT(m.mechanism->home().position_mm.y(), 100.0);
  const ActuatorVector q = *m.mechanism->inverse(m.mechanism->home());
  EXPECT_NEAR(q[0], 300.0, 1e-9);  // equilateral without limits
  EXPECT_NEAR(q[1], 300.0, 1e-9);
  EXPECT_EQ(controlled_coordinate_names(*m.mechanism), (std::vector<std::string>{"x", "y"}));
}

TEST(Planar2MachineFile, ErrorsNameFileLineAndKey) {
  EXPECT_NE(planar2_load_error("type: planar2\nhome: [1, 2]\n").find("bad.yaml:1:1: base_joints: missing"),
            std::string::npos);
  EXPECT_NE(planar2_load_error("type: planar2\nbase_joint:\n  - [0, 0]\n  - [1, 0]\n")
                .find("bad.yaml:2:1: base_joint: unknown key"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[0, 0]", "[300, 40]", "  - [1, 1]\n"))
                .find("bad.yaml:3:3: base_joints: expected a list of 2 points of 2 numbers, got 3 points"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[0, 0]", "[300, 40, 0]"))
                .find("bad.yaml:4:5: base_joints[1]: expected 2 numbers, got 3"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[0, 0]", "[300, 40]", "home: [1, 2, 3]\n"))
                .find("bad.yaml:5:7: home: expected a list of 2 numbers, got 3"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[0, 0]", "[300, 40]", "tool: [0, 10]\n"))
                .find("bad.yaml:5:7: tool: planar2 has no platform"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[0, 0]", "[300, 40]", "home: [150, 20]\n"))
                .find("bad.yaml:5:7: home: planar2 is singular"),
            std::string::npos);
  EXPECT_NE(planar2_load_error(planar2_yaml("[7, 7]", "[7, 7]"))
                .find("bad.yaml:3:3: base_joints: A1 and A2 coincide"),
            std::string::npos);
}

}  // namespace
}  // namespace pkm
