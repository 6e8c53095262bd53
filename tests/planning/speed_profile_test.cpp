// The one-dimensional speed profile: caps respected, accelerations within bounds, erosion conservative.
#include "planning/speed_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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
  erode_caps(p, 0.05, 0.5);
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

/// The moving average of the planned motion over `window_s`, sampled every `dt_s`: at each time the filtered
/// speed (s(t) − s(t − T))/T against the larger of the two given caps around the filtered position (the plan
/// moves with constant acceleration between samples, so between them it is below the larger one).
double worst_filtered_speed_ratio(const ProfileSamples& p, const std::vector<double>& caps, double window_s,
                                  double dt_s) {
  const TimedProfile timed = time_profile(p);
  ProfileCursor cursor(p, timed);
  const auto ticks = static_cast<std::size_t>(std::round(window_s / dt_s));
  std::vector<double> history;
  double sum = 0.0, worst = 0.0;
  for (double t = 0.0; t <= timed.end_time_s + window_s; t += dt_s) {
    const double s = cursor.position_at(t);
    history.push_back(s);
    sum += s;
    const double oldest = history.size() > ticks ? history[history.size() - 1 - ticks] : 0.0;
    if (history.size() > ticks) sum -= oldest;
    const double filtered = sum / static_cast<double>(ticks);
    const double speed = (s - oldest) / window_s;
    const auto after = std::upper_bound(p.s.begin(), p.s.end(), filtered) - p.s.begin();
    const std::size_t j = std::clamp<std::size_t>(after, 1, p.size() - 1);
    const double cap = std::max(caps[j - 1], caps[j]);
    if (speed > 1e-9) worst = std::max(worst, cap > 0.0 ? speed / cap : 1e9);
  }
  return worst;
}

TEST(SpeedProfile, TheFilteredPlanStaysUnderEveryCap) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    ProfileSamples p = random_samples(rng, 400);
    const std::vector<double> caps = p.speed_cap;
    for (std::size_t i = 0; i < p.size(); ++i) p.hold_s[i] = p.stop[i] ? 0.05 : 0.0;
    erode_caps(p, 0.05, 0.0);
    plan_speeds(p);
    EXPECT_LE(worst_filtered_speed_ratio(p, caps, 0.05, 1e-4), 1.0 + 1e-3) << "trial " << trial;
  }
}

// A slow point 20 mm into a 100 mm rapid: the filter's window (T = 0.1 s) spans T·0.5 mm/s of path there,
// so only the stretch around the point is slow. The erosion's reach used to come from the unfiltered
// 100 mm/s plan (T·v + a·T²/2 = 17.5 mm each side), and the rapid up to the slow point crept at 0.5 mm/s.
TEST(SpeedProfile, ASlowPointSlowsOnlyItsNeighbourhood) {
  ProfileSamples p;
  p.resize(1001);
  for (std::size_t i = 0; i <= 1000; ++i) {
    p.s[i] = 0.1 * static_cast<double>(i);
    p.speed_cap[i] = i == 200 ? 0.5 : 100.0;
    p.accel_cap[i] = 1500.0;
    p.stop[i] = i == 0 || i == 1000;
    p.hold_s[i] = p.stop[i] ? 0.1 : 0.0;
  }
  p.speed_cap.front() = p.speed_cap.back() = 0.0;
  const std::vector<double> caps = p.speed_cap;
  erode_caps(p, 0.1, 0.0);
  plan_speeds(p);
  EXPECT_LE(worst_filtered_speed_ratio(p, caps, 0.1, 1e-4), 1.0 + 1e-3);
  // Unfiltered optimum: about 1.1 s of cruising and braking plus the slow stretch; 1.5 mm at 0.5 mm/s is 3 s.
  EXPECT_LT(time_profile(p).end_time_s, 5.0);
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
