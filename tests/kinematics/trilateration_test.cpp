// Three-sphere trilateration: the quaternion algorithm (56)–(59) of Smirnov 2019, §2.3.3, against
// independently derived values, the classical form against it on random cases, and the degenerate cases.
#include "kinematics/trilateration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/rotation.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

const double kSqrt3 = std::sqrt(3.0);

// The derived case: joints on a 400 mm circle, B = (37, −52, 480).
std::array<Eigen::Vector3d, 3> reference_joints() {
  return {Eigen::Vector3d(400, 0, 0), Eigen::Vector3d(-200, 200 * kSqrt3, 0),
          Eigen::Vector3d(-200, -200 * kSqrt3, 0)};
}

std::array<double, 3> lengths_to(const std::array<Eigen::Vector3d, 3>& a, const Eigen::Vector3d& b) {
  return {(b - a[0]).norm(), (b - a[1]).norm(), (b - a[2]).norm()};
}

TEST(Trilateration, Section61bQuaternionIntermediateValues) {
  const auto a = reference_joints();
  const Eigen::Vector3d b(37, -52, 480);
  const auto l = lengths_to(a, b);
  EXPECT_NEAR(l[0], 604.047184, 1e-6);
  EXPECT_NEAR(l[1], 667.307768, 1e-6);
  EXPECT_NEAR(l[2], 610.938903, 1e-6);

  const QuaternionTrilateration q = quaternion_trilateration(a, l);
  ASSERT_EQ(q.status, TrilaterationStatus::two_points);
  EXPECT_EQ(q.count, 2);
  EXPECT_NEAR(q.a11, -346.410162, 1e-6);
  EXPECT_NEAR(q.a12, -600.0, 1e-9);
  EXPECT_NEAR(q.a21, -692.820323, 1e-6);
  EXPECT_NEAR(q.a22, 0.0, 1e-9);
  EXPECT_NEAR(q.b1, -209.958090, 1e-6);
  EXPECT_NEAR(q.b2, -206.821103, 1e-6);
  EXPECT_NEAR(q.lambda01, 0.29852055, 1e-8);
  EXPECT_NEAR(q.lambda02, 0.17757923, 1e-8);
  // '+' root: λ0 = 0.92717535 (λ0² = 0.859654), λ1 = 0.32196773, λ2 = 0.19152713, and B exactly.
  EXPECT_NEAR(q.plus.lambda0, 0.92717535, 1e-8);
  EXPECT_NEAR(q.plus.lambda0 * q.plus.lambda0, 0.859654, 1e-6);
  EXPECT_NEAR(q.plus.lambda1, 0.32196773, 1e-8);
  EXPECT_NEAR(q.plus.lambda2, 0.19152713, 1e-8);
  EXPECT_LT((q.plus.point_mm - b).norm(), 1e-9);
  // '−' root: λ0² = 0.140346 and the mirror image (37, −52, −480).
  EXPECT_NEAR(q.minus.lambda0 * q.minus.lambda0, 0.140346, 1e-6);
  EXPECT_LT((q.minus.point_mm - Eigen::Vector3d(37, -52, -480)).norm(), 1e-9);
  // Each root is a unit quaternion with λ3 = 0 that turns the vertical rod (0, 0, L2) onto A2B (eq. 48, 54).
  for (const QuaternionRoot& root : {q.plus, q.minus}) {
    const Eigen::Quaterniond rotation(root.lambda0, root.lambda1, root.lambda2, 0.0);
    EXPECT_NEAR(rotation.norm(), 1.0, 1e-12);
    EXPECT_LT((rotation * Eigen::Vector3d(0, 0, l[1]) + a[1] - root.point_mm).norm(), 1e-9);
  }
}

TEST(Trilateration, Section61bClassicalGivesTheSameTwoPoints) {
  const auto a = reference_joints();
  const auto l = lengths_to(a, Eigen::Vector3d(37, -52, 480));
  const SphereIntersection s = intersect_three_spheres(a, l);
  ASSERT_EQ(s.status, TrilaterationStatus::two_points);
  EXPECT_EQ(s.count, 2);
  EXPECT_LT((s.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-15);  // counter-clockwise joints: normal up
  EXPECT_LT((s.above_mm - Eigen::Vector3d(37, -52, 480)).norm(), 1e-9);
  EXPECT_LT((s.below_mm - Eigen::Vector3d(37, -52, -480)).norm(), 1e-9);
  EXPECT_NEAR(s.height_mm, 480.0, 1e-9);
}

TEST(Trilateration, ClassicalAndQuaternionAgreeOnRandomLevelCases) {
  std::mt19937_64 rng(20190561);
  for (int i = 0; i < 2000; ++i) {
    const double z0 = test::uniform(rng, -300, 300);
    std::array<Eigen::Vector3d, 3> a;
    for (auto& p : a) p = Eigen::Vector3d(test::uniform(rng, -500, 500), test::uniform(rng, -500, 500), z0);
    const Eigen::Vector3d u = a[1] - a[0], v = a[2] - a[0];
    if (u.cross(v).norm() < 0.05 * u.norm() * v.norm()) continue;  // nearly collinear: ill-conditioned
    const Eigen::Vector3d b(test::uniform(rng, -600, 600), test::uniform(rng, -600, 600),
                            z0 + test::uniform(rng, 20, 900) * (i % 2 == 0 ? 1 : -1));
    const auto l = lengths_to(a, b);
    const QuaternionTrilateration q = quaternion_trilateration(a, l);
    const SphereIntersection s = intersect_three_spheres(a, l);
    ASSERT_EQ(q.status, TrilaterationStatus::two_points);
    ASSERT_EQ(s.status, TrilaterationStatus::two_points);
    // '+' is above the joint plane in the quaternion form; the classical form orders by its normal.
    const bool normal_up = s.normal.z() > 0;
    const Eigen::Vector3d classical_up = normal_up ? s.above_mm : s.below_mm;
    const Eigen::Vector3d classical_down = normal_up ? s.below_mm : s.above_mm;
    EXPECT_LT((q.plus.point_mm - classical_up).norm(), 1e-7);
    EXPECT_LT((q.minus.point_mm - classical_down).norm(), 1e-7);
    EXPECT_LT(((b.z() > z0 ? q.plus.point_mm : q.minus.point_mm) - b).norm(), 1e-7);
    EXPECT_GT(q.plus.point_mm.z(), z0);
    EXPECT_LT(q.minus.point_mm.z(), z0);
  }
}

TEST(Trilateration, ClassicalWorksInAnyFrame) {
  std::mt19937_64 rng(42);
  for (int i = 0; i < 1000; ++i) {
    std::array<Eigen::Vector3d, 3> a;
    for (auto& p : a)
      p = Eigen::Vector3d(test::uniform(rng, -500, 500), test::uniform(rng, -500, 500),
                          test::uniform(rng, -500, 500));
    const Eigen::Vector3d u = a[1] - a[0], v = a[2] - a[0];
    if (u.cross(v).norm() < 0.05 * u.norm() * v.norm()) continue;
    const Eigen::Vector3d b(test::uniform(rng, -800, 800), test::uniform(rng, -800, 800),
                            test::uniform(rng, -800, 800));
    const SphereIntersection s = intersect_three_spheres(a, lengths_to(a, b));
    if (s.height_mm < 1.0) continue;  // nearly in the centre plane: the height is ill-conditioned
    ASSERT_EQ(s.status, TrilaterationStatus::two_points);
    const double side = s.normal.dot(b - a[0]);
    EXPECT_LT(((side > 0 ? s.above_mm : s.below_mm) - b).norm(), 1e-7);
    // Both points satisfy all three sphere equations.
    for (const Eigen::Vector3d& p : {s.above_mm, s.below_mm}) {
      for (int j = 0; j < 3; ++j) EXPECT_NEAR((p - a[j]).norm(), (b - a[j]).norm(), 1e-7);
    }
  }
}

TEST(Trilateration, TouchingSpheresGiveOnePoint) {
  const auto a = reference_joints();
  const Eigen::Vector3d b(37, -52, 0);  // in the joint plane: both roots coincide
  const auto l = lengths_to(a, b);
  const SphereIntersection s = intersect_three_spheres(a, l);
  EXPECT_EQ(s.status, TrilaterationStatus::one_point);
  EXPECT_EQ(s.count, 1);
  EXPECT_LT((s.above_mm - b).norm(), 1e-6);
  const QuaternionTrilateration q = quaternion_trilateration(a, l);
  EXPECT_EQ(q.status, TrilaterationStatus::one_point);
  EXPECT_EQ(q.count, 1);
  EXPECT_LT((q.plus.point_mm - b).norm(), 1e-6);
}

TEST(Trilateration, InfeasibleLengthsAreReported) {
  const auto a = reference_joints();
  const std::array<double, 3> short_rods{100.0, 100.0, 100.0};  // the spheres do not meet
  const SphereIntersection s = intersect_three_spheres(a, short_rods);
  EXPECT_EQ(s.status, TrilaterationStatus::infeasible_lengths);
  EXPECT_EQ(s.count, 0);
  const QuaternionTrilateration q = quaternion_trilateration(a, short_rods);
  EXPECT_EQ(q.status, TrilaterationStatus::infeasible_lengths);
  EXPECT_EQ(q.count, 0);
  EXPECT_EQ(intersect_three_spheres(a, {600.0, -1.0, 600.0}).status, TrilaterationStatus::infeasible_lengths);
  EXPECT_EQ(quaternion_trilateration(a, {600.0, 0.0, 600.0}).status, TrilaterationStatus::infeasible_lengths);
}

TEST(Trilateration, CollinearCentresAreReported) {
  const std::array<Eigen::Vector3d, 3> line{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(100, 50, 0),
                                            Eigen::Vector3d(300, 150, 0)};
  const std::array<double, 3> l{500.0, 500.0, 500.0};
  const SphereIntersection s = intersect_three_spheres(line, l);
  EXPECT_EQ(s.status, TrilaterationStatus::collinear_centres);
  EXPECT_EQ(s.count, 0);
  const QuaternionTrilateration q = quaternion_trilateration(line, l);
  EXPECT_EQ(q.status, TrilaterationStatus::collinear_centres);
  EXPECT_EQ(q.count, 0);
  const std::array<Eigen::Vector3d, 3> coincident{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0),
                                                  Eigen::Vector3d(300, 150, 0)};
  EXPECT_EQ(intersect_three_spheres(coincident, l).status, TrilaterationStatus::collinear_centres);
}

TEST(Trilateration, QuaternionFormNeedsLevelCentres) {
  auto a = reference_joints();
  a[2].z() = 1.0;
  const auto l = lengths_to(a, Eigen::Vector3d(37, -52, 480));
  EXPECT_EQ(quaternion_trilateration(a, l).status, TrilaterationStatus::centres_not_level);
  // The classical form does not care.
  const SphereIntersection s = intersect_three_spheres(a, l);
  EXPECT_EQ(s.status, TrilaterationStatus::two_points);
  EXPECT_LT((s.above_mm - Eigen::Vector3d(37, -52, 480)).norm(), 1e-9);
}

TEST(Trilateration, RodStraightAboveTheReferenceJointHasAWellDefinedMinusRoot) {
  // λ01 = λ02 = 0: the '−' root has λ0 = 0 (a half turn); (58) would divide by zero.
  const auto a = reference_joints();
  const QuaternionTrilateration q =
      quaternion_trilateration(a, lengths_to(a, a[1] + Eigen::Vector3d(0, 0, 300)));
  ASSERT_EQ(q.status, TrilaterationStatus::two_points);
  EXPECT_LT((q.plus.point_mm - (a[1] + Eigen::Vector3d(0, 0, 300))).norm(), 1e-9);
  EXPECT_LT((q.minus.point_mm - (a[1] - Eigen::Vector3d(0, 0, 300))).norm(), 1e-9);
  EXPECT_TRUE(std::isfinite(q.minus.lambda1) && std::isfinite(q.minus.lambda2));
  EXPECT_NEAR(q.minus.lambda0 * q.minus.lambda0 + q.minus.lambda1 * q.minus.lambda1 +
                  q.minus.lambda2 * q.minus.lambda2,
              1.0, 1e-12);
}

TEST(Trilateration, StatusNamesAreReadable) {
  EXPECT_STREQ(to_string(TrilaterationStatus::collinear_centres), "the three centres are collinear");
}

}  // namespace
}  // namespace pkm
