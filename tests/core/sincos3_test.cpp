// The three-angle sine and cosine of the IK hot path (core/sincos3.hpp): within one unit in the last place of
// the C library's, the AVX2 and AVX-512 copies bit for bit the SSE2 one, signed zeros and the fallback for
// huge or non-finite angles; rotation_from_angles' AVX2 copy bit for bit its baseline. The AVX-512 copy is
// compared where the processor has it.
#include "core/sincos3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/rotation_kernels.hpp"
#include "core/wide_kernels.hpp"

namespace pkm {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every copy the processor runs (AVX2, AVX-512) against the baseline.
void sincos3_both(const double* angles, double* sines, double* cosines, bool& copies_agree) {
  sincos3_baseline(angles, sines, cosines);
  copies_agree = true;
#if PKM_HAS_WIDE_KERNELS
  if (!wide_kernels_available()) return;
  double wide_sines[3], wide_cosines[3];
  sincos3_avx2(angles, wide_sines, wide_cosines);
  for (int k = 0; k < 3; ++k) {
    copies_agree =
        copies_agree && same_bits(wide_sines[k], sines[k]) && same_bits(wide_cosines[k], cosines[k]);
  }
  if (!avx512_kernels_available()) return;
  sincos3_avx512(angles, wide_sines, wide_cosines);
  for (int k = 0; k < 3; ++k) {
    copies_agree =
        copies_agree && same_bits(wide_sines[k], sines[k]) && same_bits(wide_cosines[k], cosines[k]);
  }
#endif
}

TEST(Sincos3, WithinOneUlpOfTheLibraryOnEveryRange) {
  std::mt19937_64 rng(7);
  for (const double range : {0.2, 0.785, 1.0, 3.2, 7.0, 100.0, 1e5}) {
    std::uniform_real_distribution<double> u(-range, range);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const double angles[3] = {u(rng), u(rng), u(rng)};
      double s[3], c[3];
      bool agree = false;
      sincos3_both(angles, s, c, agree);
      ASSERT_TRUE(agree) << angles[0] << " " << angles[1] << " " << angles[2];
      for (int k = 0; k < 3; ++k) {
        worst = std::max({worst, std::abs(s[k] - std::sin(angles[k])), std::abs(c[k] - std::cos(angles[k]))});
      }
    }
    EXPECT_LE(worst, 1.2e-16) << "range " << range;
  }
}

TEST(Sincos3, ExactAtTheSpecialAngles) {
  const double angles[3] = {0.0, -0.0, 3.14159265358979323846 / 2.0};
  double s[3], c[3];
  bool agree = false;
  sincos3_both(angles, s, c, agree);
  EXPECT_TRUE(agree);
  EXPECT_TRUE(same_bits(s[0], 0.0));
  EXPECT_TRUE(same_bits(s[1], -0.0));  // sin(−0) = −0
  EXPECT_EQ(c[0], 1.0);
  EXPECT_EQ(c[1], 1.0);
  EXPECT_EQ(s[2], 1.0);
  EXPECT_EQ(c[2], std::cos(angles[2]));
}

TEST(Sincos3, HugeAndNonFiniteAnglesGoToTheLibrary) {
  const double angles[3] = {1e6, std::numeric_limits<double>::infinity(), 0.5};
  double s[3], c[3];
  bool agree = false;
  sincos3_both(angles, s, c, agree);
  EXPECT_TRUE(agree);
  for (int k = 0; k < 3; ++k) {
    if (std::isfinite(std::sin(angles[k]))) {
      EXPECT_TRUE(same_bits(s[k], std::sin(angles[k]))) << k;
      EXPECT_TRUE(same_bits(c[k], std::cos(angles[k]))) << k;
    } else {
      EXPECT_TRUE(std::isnan(s[k]) && std::isnan(c[k])) << k;
    }
  }
  const double nan_angles[3] = {std::nan(""), 0.1, 0.2};
  sincos3_both(nan_angles, s, c, agree);
  EXPECT_TRUE(std::isnan(s[0]) && std::isnan(c[0]));
  EXPECT_EQ(s[1], std::sin(0.1));
}

TEST(Sincos3, RotationFromAnglesTheSameBitsInBothCopies) {
  std::mt19937_64 rng(13);
  for (const double range : {0.5, 0.8, 3.0, 1e6}) {
    std::uniform_real_distribution<double> u(-range, range);
    for (int i = 0; i < 5000; ++i) {
      const Eigen::Vector3d angles(u(rng), u(rng), u(rng));
      for (const AngleConvention convention :
           {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
        const Eigen::Matrix3d hot = rotation_from_angles(convention, angles),
                              baseline = rotation_from_angles_baseline(convention, angles);
        ASSERT_EQ(std::memcmp(hot.data(), baseline.data(), sizeof(double) * 9), 0)
            << to_string(convention) << " " << angles.transpose();
        EXPECT_LE((hot - rotation_from_elementary_product(convention, angles)).cwiseAbs().maxCoeff(), 1e-15);
      }
    }
  }
}

}  // namespace
}  // namespace pkm
