// The one-dimensional speed profile: caps respected, accelerations within bounds, erosion conservative.
#include "planning/speed_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pkm::planning {
namespace {

ProfileSamples random_samples(std::mt19937_64& rng, std::size_t n) {
  ProfileSamples p;
  p.resize(n);
  std::uniform_real_distribution<double> step(0.1, 2.0), cap(5.0, 200.0), accel(100.0, 2000.0);
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    p.s[i] = s;
    s += step(rng);
    p.speed_cap[i] = cap(rng);
    p.accel_cap[i] = accel(rng);
    p.stop[i] = i == 0 || i + 1 == n || (i % 97 == 0);
    if (p.stop[i]) p.speed_cap[i] = 0.0;
  }
  return p;
}

TEST(SpeedProfile, PassesRespectCapsAndAccelerationBetweenSamples) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    ProfileSamples p = random_samples(rng, 500);
    plan_speeds(p);
    EXPECT_EQ(p.speed.front(), 0.0);
    EXPECT_EQ(p.speed.back(), 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_LE(p.speed[i], p.speed_cap[i] + 1e-12);
      EXPECT_GE(p.speed[i], 0.0);
      if (i + 1 < p.size()) {
        const double a = std::min(p.accel_cap[i], p.accel_cap[i + 1]);
        const double dv2 = p.speed[i + 1] * p.speed[i + 1] - p.speed[i] * p.speed[i];
        EXPECT_LE(std::abs(dv2), 2.0 * a * (p.s[i + 1] - p.s[i]) * (1 + 1e-12) + 1e-12);
      }
    }
  }
}

TEST(SpeedProfile, PassesAreTimeOptimalOnAConstantCap) {
  // 100 mm at a 50 mm/s cap with 1000 mm/s²: accelerate 1.25 mm, cruise, brake 1.25 mm.
  ProfileSamples p;
  p.resize(1001);
  for (std::size_t i = 0; i <= 1000; ++i) {
    p.s[i] = 0.1 * static_cast<double>(i);
    p.speed_cap[i] = 50.0;
    p.accel_cap[i] = 1000.0;
    p.stop[i] = i == 0 || i == 1000;
  }
  p.speed_cap.front() = p.speed_cap.back() = 0.0;
  plan_speeds(p);
  const TimedProfile timed = time_profile(p);
  // Optimal on the grid: only the interval where the cap is reached averages the acceleration.
  EXPECT_NEAR(timed.end_time_s, 100.0 / 50.0 + 50.0 / 1000.0, 1e-4);
}

TEST(SpeedProfile, ErosionOnlyLowersCapsAndNeverCrossesAStop) {
  std::mt19937_64 rng(11);
  ProfileSamples p = random_samples(rng, 2000);
  const ProfileSamples before = p;
  plan_speeds(p);
  erode_caps(p, 0.05, 1000.0, 0.5);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LE(p.speed_cap[i], before.speed_cap[i]);
    EXPECT_LE(p.accel_cap[i], before.accel_cap[i]);
    if (p.stop[i]) {
      EXPECT_EQ(p.speed_cap[i], 0.0);
    } else {
      EXPECT_GT(p.speed_cap[i], 0.0) << "a stop's zero cap leaked to sample " << i;
    }
  }
}

TEST(SpeedProfile, CursorIsContinuousAndMonotone) {
  std::mt19937_64 rng(3);
  ProfileSamples p = random_samples(rng, 300);
  for (std::size_t i = 0; i < p.size(); ++i) p.hold_s[i] = p.stop[i] ? 0.05 : 0.0;
  plan_speeds(p);
  const TimedProfile timed = time_profile(p);
  ProfileCursor cursor(p, timed);
  double previous = 0.0;
  const double h = 1e-4;
  double max_cap = 0.0;
  for (double c : p.speed_cap) max_cap = std::max(max_cap, c);
  for (double t = 0.0; t <= timed.end_time_s + h; t += h) {
    const double s = cursor.position_at(t);
    EXPECT_GE(s, previous - 1e-12);
    EXPECT_LE(s - previous, max_cap * h * (1 + 1e-9) + 1e-12);
    previous = s;
  }
  EXPECT_NEAR(previous, p.s.back(), 1e-9);
}

}  // namespace
}  // namespace pkm::planning
