// The six struts' hot IK kernel (kinematics/strut_lengths.hpp): |p + R·b_j − a_j| to rounding, the vector
// copies bit for bit the SSE2 one, also from the six coordinates (there to rounding of the matrix's lengths).
#include "kinematics/strut_lengths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace pkm {
namespace {

TEST(SixStrutLengths, AreTheDistancesOfTheJointsAndTheSameBitsInBothCopies) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SixStrutLayout layout;
  for (int j = 0; j < 6; ++j) {
    layout.platform_mm.col(j) = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 200.0;
    layout.base_mm.col(j) = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 400.0;
  }
  for (int i = 0; i < 2000; ++i) {
    const PoseVector c =
        (PoseVector() << 50 * u(rng), 50 * u(rng), 500 + 50 * u(rng), u(rng), u(rng), u(rng)).finished();
    const Pose pose = pose_from_vector(AngleConvention::abc, c);
    double lengths[6], baseline[6];
    EXPECT_TRUE(six_strut_lengths(layout, pose, lengths));
    EXPECT_TRUE(six_strut_lengths_baseline(layout, pose, baseline));
    EXPECT_EQ(std::memcmp(lengths, baseline, sizeof lengths), 0) << i;
    for (int j = 0; j < 6; ++j) {
      const double expected = (pose.to_base(layout.platform_mm.col(j)) - layout.base_mm.col(j)).norm();
      EXPECT_NEAR(lengths[j], expected, 1e-12) << i << " " << j;
    }
  }
}

// From the coordinates (six_strut_lengths_at): every copy the processor runs gives the bits of the baseline
// copy, and the lengths of pose_from_vector's matrix to a few units in the last place, in every convention,
// with and without the angles' range reduction and for angles the C library takes.
TEST(SixStrutLengths, FromTheCoordinatesTheSameBitsInEveryCopy) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SixStrutLayout layout;
  for (int j = 0; j < 6; ++j) {
    layout.platform_mm.col(j) = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 200.0;
    layout.base_mm.col(j) = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 400.0;
  }
  const int copies = strut_kernel_count();
  EXPECT_GE(copies, 1);
  double worst_ulps = 0.0;
  for (const double range : {0.5, 0.78, 3.0, 40.0, 2e6}) {
    for (int i = 0; i < 1000; ++i) {
      const PoseVector c = (PoseVector() << 50 * u(rng), 50 * u(rng), 500 + 50 * u(rng), range * u(rng),
                            range * u(rng), range * u(rng))
                               .finished();
      for (const AngleConvention convention :
           {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
        double from_matrix[6];
        const bool reachable =
            six_strut_lengths_baseline(layout, pose_from_vector(convention, c), from_matrix);
        double expected[6];
        EXPECT_EQ(six_strut_lengths_at_kernel(0, layout, convention, c, expected), reachable);
        for (int j = 0; j < 6; ++j) {
          const double ulp = std::nextafter(from_matrix[j], INFINITY) - from_matrix[j];
          worst_ulps = std::max(worst_ulps, std::abs(expected[j] - from_matrix[j]) / ulp);
        }
        double lengths[6];
        EXPECT_EQ(six_strut_lengths_at(layout, convention, c, lengths), reachable);
        EXPECT_EQ(std::memcmp(lengths, expected, sizeof lengths), 0) << range << " " << i;
        for (int copy = 1; copy < copies; ++copy) {
          EXPECT_EQ(six_strut_lengths_at_kernel(copy, layout, convention, c, lengths), reachable);
          ASSERT_EQ(std::memcmp(lengths, expected, sizeof lengths), 0)
              << "copy " << copy << " " << to_string(convention) << " " << c.transpose();
        }
      }
    }
  }
  // Lengths of 100–1000 mm from joints of up to 400 mm: a few units of the last place of the joints'
  // coordinates, which is some units of the length's.
  EXPECT_LE(worst_ulps, 16.0);
  EXPECT_GT(worst_ulps, 0.0);  // the two forms do round differently: the comparison above is not vacuous
}

TEST(SixStrutLengths, FalseWhenAPlatformJointIsOnItsBaseJoint) {
  SixStrutLayout layout;
  for (int j = 0; j < 6; ++j) {
    layout.platform_mm.col(j) = Eigen::Vector3d(100.0 * j, 50.0, 0.0);
    layout.base_mm.col(j) = Eigen::Vector3d(120.0 * j, -40.0, 0.0);
  }
  Pose pose;
  pose.position_mm = Eigen::Vector3d(0.0, 0.0, 400.0);
  double lengths[6];
  EXPECT_TRUE(six_strut_lengths(layout, pose, lengths));
  for (int collapsed = 0; collapsed < 6; ++collapsed) {
    SixStrutLayout touching = layout;
    touching.base_mm.col(collapsed) = pose.to_base(layout.platform_mm.col(collapsed));
    EXPECT_FALSE(six_strut_lengths(touching, pose, lengths)) << collapsed;
    EXPECT_FALSE(six_strut_lengths_baseline(touching, pose, lengths)) << collapsed;
    EXPECT_EQ(lengths[collapsed], 0.0);
    const PoseVector c = vector_from_pose(AngleConvention::abc, pose);
    for (int copy = 0; copy < strut_kernel_count(); ++copy) {
      EXPECT_FALSE(six_strut_lengths_at_kernel(copy, touching, AngleConvention::abc, c, lengths)) << copy;
    }
  }
}

}  // namespace
}  // namespace pkm
