#include "core/rotation.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/units.hpp"

namespace pkm {
namespace {

TEST(Rotation, KrylovIsEquation15Literal) {
  // Dissertation eq. 15 entries, laid out as [[l1,l2,l3],[m1,m2,m3],[n1,n2,n3]].
  const double psi = 0.3, theta = -0.2, gamma = 0.5;
  const double sp = std::sin(psi), cp = std::cos(psi), st = std::sin(theta), ct = std::cos(theta),
               sg = std::sin(gamma), cg = std::cos(gamma);
  Eigen::Matrix3d expected;
  expected << cp * cg + st * sp * sg, sp * ct, -cp * sg + sp * st * cg,  //
      -sp * cg + st * cp * sg, cp * ct, sp * sg + cp * st * cg,          //
      ct * sg, -st, ct * cg;
  const Eigen::Matrix3d r = rotation_from_angles(AngleConvention::krylov, {psi, theta, gamma});
  EXPECT_LT((r - expected).norm(), 1e-15);
}

TEST(Rotation, ClosedFormsEqualTheElementaryProducts) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> any(-kPi, kPi);
  for (AngleConvention c : {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    for (int i = 0; i < 1000; ++i) {
      const Eigen::Vector3d a(any(rng), any(rng), any(rng));
      EXPECT_LT((rotation_from_angles(c, a) - rotation_from_elementary_product(c, a)).norm(), 1e-14)
          << to_string(c);
    }
  }
  EXPECT_LT((rotation_from_elementary_product(AngleConvention::krylov, {0.1, 0.2, 0.3}) -
             rot_z(-0.1) * rot_x(-0.2) * rot_y(-0.3))
                .norm(),
            1e-15);
  EXPECT_LT((rotation_from_elementary_product(AngleConvention::euler_zxz, {0.1, 0.2, 0.3}) -
             rot_z(0.1) * rot_x(0.2) * rot_z(0.3))
                .norm(),
            1e-15);
}

TEST(Rotation, AbcIsFixedAxisXyz) {
  const Eigen::Vector3d abc(0.1, -0.4, 0.7);
  const Eigen::Matrix3d r = rotation_from_angles(AngleConvention::abc, abc);
  EXPECT_LT((r - rot_z(0.7) * rot_y(-0.4) * rot_x(0.1)).norm(), 1e-15);
}

TEST(Rotation, AnglesRoundTripInEveryConvention) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-kPi, kPi), middle(-1.5, 1.5), nutation(0.05, 3.09);
  for (AngleConvention c : {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3d a(any(rng), c == AngleConvention::euler_zxz ? nutation(rng) : middle(rng),
                              any(rng));
      const Eigen::Matrix3d r = rotation_from_angles(c, a);
      EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
      const Eigen::Vector3d back = angles_from_rotation(c, r);
      EXPECT_LT((back - a).norm(), 1e-9) << to_string(c);
      EXPECT_LT((quaternion_from_angles(c, a).toRotationMatrix() - r).norm(), 1e-14);
    }
  }
}

TEST(Rotation, SingularMiddleAngleStillGivesTheSameMatrix) {
  for (AngleConvention c : {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    const double middle = c == AngleConvention::euler_zxz ? kPi : kPi / 2;
    const Eigen::Vector3d a(0.4, middle, -0.9);
    const Eigen::Matrix3d r = rotation_from_angles(c, a);
    EXPECT_LT((rotation_from_angles(c, angles_from_rotation(c, r)) - r).norm(), 1e-12) << to_string(c);
    EXPECT_LT(distance_from_angle_singularity(c, a), 1e-12);
  }
}

TEST(Rotation, AngularVelocityMatrixMatchesFiniteDifference) {
  const Eigen::Vector3d a(0.3, 0.2, -0.6);
  for (AngleConvention c : {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    const Eigen::Matrix3d e = angular_velocity_matrix(c, a);
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      Eigen::Vector3d ap = a, am = a;
      ap[k] += h;
      am[k] -= h;
      const Eigen::Matrix3d dr = (rotation_from_angles(c, ap) - rotation_from_angles(c, am)) / (2 * h);
      const Eigen::Matrix3d w = dr * rotation_from_angles(c, a).transpose();
      EXPECT_LT((Eigen::Vector3d(w(2, 1), w(0, 2), w(1, 0)) - e.col(k)).norm(), 1e-8) << to_string(c);
    }
  }
}

TEST(Rotation, QuaternionRotatesAsEquation46) {
  // Eq. 46 in coordinates, Hamilton's rule.
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.8, 0.1, -0.3, 0.5).normalized();
  const double l0 = q.w(), l1 = q.x(), l2 = q.y(), l3 = q.z();
  const Eigen::Vector3d r(3, -2, 7);
  const Eigen::Vector3d expected((l0 * l0 + l1 * l1 - l2 * l2 - l3 * l3) * r.x() +
                                     2 * (l1 * l2 - l0 * l3) * r.y() + 2 * (l1 * l3 + l0 * l2) * r.z(),
                                 2 * (l1 * l2 + l0 * l3) * r.x() +
                                     (l0 * l0 + l2 * l2 - l1 * l1 - l3 * l3) * r.y() +
                                     2 * (l2 * l3 - l0 * l1) * r.z(),
                                 2 * (l1 * l3 - l0 * l2) * r.x() + 2 * (l2 * l3 + l0 * l1) * r.y() +
                                     (l0 * l0 + l3 * l3 - l1 * l1 - l2 * l2) * r.z());
  EXPECT_LT((q * r - expected).norm(), 1e-13);
}

TEST(Rotation, RotationVectorRoundTrip) {
  const Eigen::Vector3d w(0.3, -1.2, 2.0);
  EXPECT_LT((rotation_vector_from_rotation(rotation_from_rotation_vector(w)) - w).norm(), 1e-12);
  EXPECT_LT((rotation_from_rotation_vector(Eigen::Vector3d(1e-10, 0, 0)) - rot_x(1e-10)).norm(), 1e-20);
}

}  // namespace
}  // namespace pkm
