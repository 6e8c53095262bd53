// The path table's A B C, kept while the rotation does not change (formats/plan_files.hpp): always the angles
// of the rotation given, to the bit, including rotations that differ only in the sign of a zero (which
// atan2 turns into +180° and −180°).
#include <gtest/gtest.h>

#include <random>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "formats/plan_files.hpp"

namespace pkm::formats {
namespace {

Eigen::Vector3d fresh_abc_deg(const Eigen::Matrix3d& r) {
  return angles_from_rotation(AngleConvention::abc, r) * deg_from_rad(1.0);
}

TEST(AbcOfRotation, EqualsTheAnglesOfEveryRotationToTheBit) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  AbcOfRotation kept;
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 2000; ++k) {
    if (k % 5 == 0)  // runs of the same rotation, as a 3-axis program has
      r = rotation_from_angles(AngleConvention::abc, Eigen::Vector3d(angle(rng), angle(rng), angle(rng)));
    const Eigen::Vector3d expected = fresh_abc_deg(r);
    const Eigen::Vector3d got = kept.of(r);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(std::signbit(got[c]), std::signbit(expected[c])) << k;
    ASSERT_TRUE(got == expected) << k;
  }
  // A half turn about Z, written with +0 and with −0 where the sine vanishes: atan2 tells them apart.
  Eigen::Matrix3d plus = Eigen::Matrix3d::Zero(), minus;
  plus(0, 0) = -1.0, plus(1, 1) = -1.0, plus(2, 2) = 1.0;
  minus = plus;
  minus(1, 0) = -0.0, minus(0, 1) = -0.0;
  const Eigen::Vector3d first = kept.of(plus);
  EXPECT_TRUE(first == fresh_abc_deg(plus));
  const Eigen::Vector3d second = kept.of(minus);
  EXPECT_TRUE(second == fresh_abc_deg(minus));
  EXPECT_NE(fresh_abc_deg(plus), fresh_abc_deg(minus)) << "the case this guards against";
}

}  // namespace
}  // namespace pkm::formats
