// The Simple Matrix Scenario's Rodrigues rotation of Rusanov et al. with the printed errors corrected
// (src/core/rotation_between.hpp): on random unit vectors the corrected matrix maps the old normal onto the
// new one and is a rotation; the matrix is the exponential of the axis-angle; the printed entry (1,2) and the
// printed axis direction would not do it.
#include "core/rotation_between.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/rotation.hpp"

namespace pkm {
namespace {

Eigen::Vector3d random_rotation_between_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

TEST(RotationBetween, TheCorrectedRodriguesMatrixMapsTheOldNormalOntoTheNewOne) {
  std::mt19937_64 rng(1520);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d n_old = random_rotation_between_unit(rng);
    // Near and far: small turns as along a path, and any.
    Eigen::Vector3d n_new = random_rotation_between_unit(rng);
    if (trial % 2 == 0) n_new = (n_old + 1e-3 * (trial % 7) * n_new).normalized();
    const Eigen::Matrix3d r = rotation_between(n_old, n_new);
    EXPECT_LT((r * n_old - n_new).norm(), 1e-14) << "trial " << trial;
    EXPECT_LT((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
    // The smallest such rotation: its axis square to both normals, its angle the one between them.
    const Eigen::Vector3d turn = rotation_vector_from_rotation(r);
    EXPECT_NEAR(turn.norm(), std::atan2(n_old.cross(n_new).norm(), n_old.dot(n_new)), 1e-12);
    EXPECT_NEAR(turn.dot(n_old), 0.0, 1e-12);
  }
}

TEST(RotationBetween, RodriguesMatrixIsTheExponentialOfItsAxisAngle) {
  std::mt19937_64 rng(1521);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d axis = random_rotation_between_unit(rng);
    const double phi = angle(rng);
    EXPECT_LT((rodrigues_matrix(axis, phi) - rotation_from_rotation_vector(phi * axis)).norm(), 1e-14);
  }
}

TEST(RotationBetween, ThePrintedEntryAndAxisDirectionDoNotMapTheNormal) {
  std::mt19937_64 rng(1522);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d n_old = random_rotation_between_unit(rng),
                          n_new = random_rotation_between_unit(rng);
    const Eigen::Vector3d cross = n_old.cross(n_new);
    const double phi = std::atan2(cross.norm(), n_old.dot(n_new));
    const Eigen::Vector3d v = cross.normalized();
    // The printed entry (1,2), v_z² sin φ: not even orthogonal.
    Eigen::Matrix3d printed = rodrigues_matrix(v, phi);
    printed(0, 1) = v.x() * v.y() * (1 - std::cos(phi)) - v.z() * v.z() * std::sin(phi);
    EXPECT_GT((printed * printed.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-6);
    // The printed axis n_new × n_old turns n_old the other way: onto n_new's mirror image about n_old.
    const Eigen::Vector3d other_way = rodrigues_matrix(-v, phi) * n_old;
    EXPECT_GT((other_way - n_new).norm(), 1e-6);
    EXPECT_LT((other_way - (2 * n_old.dot(n_new) * n_old - n_new)).norm(), 1e-12);
  }
  // Equal and opposite normals.
  const Eigen::Vector3d n = random_rotation_between_unit(rng);
  EXPECT_LT((rotation_between(n, n) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  const Eigen::Matrix3d half = rotation_between(n, -n);
  EXPECT_LT((half * n + n).norm(), 1e-14);
  EXPECT_NEAR(half.determinant(), 1.0, 1e-14);
}

}  // namespace
}  // namespace pkm
