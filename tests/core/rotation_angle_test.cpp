// The angle between two orientations as a sine and cosine (src/core/rotation_angle.hpp): on random rotations,
// from a nanoradian to a half turn, it is the quaternion angular distance, and comparing two such angles
// orders them as their degrees do.
#include "core/rotation_angle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

namespace pkm {
namespace {

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
      .normalized()
      .toRotationMatrix();
}

/// `base` turned by `angle_rad` about a random axis.
Eigen::Matrix3d turned(std::mt19937_64& rng, const Eigen::Matrix3d& base, double angle_rad) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  return Eigen::AngleAxisd(angle_rad, axis).toRotationMatrix() * base;
}

TEST(RotationAngle, IsTheAngularDistanceFromANanoradianToAHalfTurn) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> exponent(-9.0, std::log10(std::numbers::pi));
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Matrix3d a = random_rotation(rng);
    const double angle_rad = std::min(std::numbers::pi, std::pow(10.0, exponent(rng)));
    const Eigen::Matrix3d b = turned(rng, a, angle_rad);
    const RotationAngle angle = rotation_angle_between(b, a);
    const double reference_deg =
        Eigen::Quaterniond(a).angularDistance(Eigen::Quaterniond(b)) * 180.0 / std::numbers::pi;
    // Both from rounded matrices: a few ulps of the entries, as an angle.
    EXPECT_NEAR(angle.degrees(), reference_deg, 1e-12 + 1e-12 * reference_deg) << angle_rad << " rad";
    EXPECT_NEAR(angle.degrees(), angle_rad * 180.0 / std::numbers::pi, 1e-10 + 1e-9 * angle_rad * 57.3);
    EXPECT_NEAR(angle.sin * angle.sin + angle.cos * angle.cos, 1.0, 1e-12);
  }
  EXPECT_EQ(rotation_angle_between(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()).degrees(), 0.0);
}

TEST(RotationAngle, ComparesAsItsDegreesDo) {
  std::mt19937_64 rng(78);
  std::uniform_real_distribution<double> angle_deg(0.0, 180.0);
  for (int trial = 0; trial < 5000; ++trial) {
    const double x = trial % 3 == 0 ? 1e-6 * angle_deg(rng) : angle_deg(rng);
    const double y = trial % 5 == 0 ? x * (1.0 + 1e-6) : angle_deg(rng);
    const RotationAngle a = RotationAngle::of_degrees(x), b = RotationAngle::of_degrees(y);
    EXPECT_EQ(a.exceeds(b), x > y) << x << " vs " << y;
    EXPECT_EQ(b.exceeds(a), y > x) << y << " vs " << x;
    EXPECT_FALSE(a.exceeds(a));
  }
  const RotationAngle unmeasured{std::nan(""), std::nan("")};
  EXPECT_FALSE(unmeasured.exceeds(RotationAngle{}));
  EXPECT_FALSE(RotationAngle::of_degrees(10.0).exceeds(unmeasured));
  EXPECT_TRUE(std::isnan(unmeasured.degrees()));
}

}  // namespace
}  // namespace pkm
