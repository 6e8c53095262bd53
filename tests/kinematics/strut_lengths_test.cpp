// The six struts' hot IK kernel (kinematics/strut_lengths.hpp): |p + R·b_j − a_j| to rounding, the vector
// copies bit for bit the SSE2 one, also from the six coordinates.
#include "kinematics/strut_lengths.hpp"

#include <gtest/gtest.h>

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

// From the coordinates (six_strut_lengths_at): every copy the processor runs gives the bits of
// pose_from_vector and the baseline lanes, in every convention, with and without the angles' range reduction
// and for angles the C library takes.
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
  for (const double range : {0.5, 0.78, 3.0, 40.0, 2e6}) {
    for (int i = 0; i < 1000; ++i) {
      const PoseVector c = (PoseVector() << 50 * u(rng), 50 * u(rng), 500 + 50 * u(rng), range * u(rng),
                            range * u(rng), range * u(rng))
                               .finished();
      for (const AngleConvention convention :
           {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
        const Pose pose = pose_from_vector(convention, c);
        double expected[6];
        const bool reachable = six_strut_lengths_baseline(layout, pose, expected);
        double lengths[6];
        EXPECT_EQ(six_strut_lengths_at(layout, convention, c, lengths), reachable);
        EXPECT_EQ(std::memcmp(lengths, expected, sizeof lengths), 0) << range << " " << i;
        for (int copy = 0; copy < copies; ++copy) {
          EXPECT_EQ(six_strut_lengths_at_kernel(copy, layout, convention, c, lengths), reachable);
          ASSERT_EQ(std::memcmp(lengths, expected, sizeof lengths), 0)
              << "copy " << copy << " " << to_string(convention) << " " << c.transpose();
        }
      }
    }
  }
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
