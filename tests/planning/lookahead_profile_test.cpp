// The look-ahead window: the whole path's plan where the window holds the braking distance, a plan within
// every cap and acceleration where it does not, and memory set by the window, not by the path.
#include "planning/lookahead_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace pkm::planning {
namespace {

constexpr double kFastest = 200.0;
constexpr double kFilterS = 0.05;

struct Generated {
  ProfileSamples samples;
  std::vector<int> move;
};

/// A path of random spacing, caps, holds and stops, with a few long fast stretches between slow places.
Generated random_path(std::mt19937_64& rng, std::size_t n) {
  Generated g;
  ProfileSamples& p = g.samples;
  p.resize(n);
  g.move.resize(n);
  std::uniform_real_distribution<double> step(0.05, 2.0), cap(5.0, kFastest), accel(100.0, 2000.0),
      unit(0.0, 1.0);
  double s = 0.0;
  int move = 0;
  for (std::size_t i = 0; i < n; ++i) {
    p.s[i] = s;
    s += step(rng);
    const bool fast = (i / 700) % 3 == 1;  // stretches where the cap stays high for hundreds of samples
    p.speed_cap[i] = fast ? kFastest * (0.9 + 0.1 * unit(rng)) : cap(rng);
    p.accel_cap[i] = accel(rng);
    p.stop[i] = i == 0 || i + 1 == n || unit(rng) < 0.002;
    p.hold_s[i] = p.stop[i] ? kFilterS : 0.0;
    if (p.stop[i]) p.speed_cap[i] = 0.0;
    if (unit(rng) < 0.3) ++move;
    g.move[i] = move;
  }
  return g;
}

LookaheadSettings settings(double max_length, int max_moves, std::size_t max_samples) {
  LookaheadSettings out;
  out.filter_window_s = kFilterS;
  out.fastest_cap = kFastest;
  out.max_length = max_length;
  out.max_moves = max_moves;
  out.max_samples = max_samples;
  return out;
}

ProfileSamples whole_plan(ProfileSamples p) {
  erode_caps(p, kFilterS, 0.0);
  plan_speeds(p);
  return p;
}

/// Every limit the whole plan's passes keep: caps (the whole path's erosion), accelerations between
/// samples, rest at stops and at the ends, and motion between samples (no two rests in a row away from
/// stops, which would cover a stretch in no time).
void expect_within_limits(const ProfileSamples& planned, const ProfileSamples& whole) {
  const std::size_t n = planned.size();
  ASSERT_EQ(n, whole.size());
  EXPECT_EQ(planned.speed.front(), 0.0);
  EXPECT_EQ(planned.speed.back(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(planned.speed_cap[i], whole.speed_cap[i]) << i;
    EXPECT_EQ(planned.accel_cap[i], whole.accel_cap[i]) << i;
    EXPECT_LE(planned.speed[i], whole.speed_cap[i]) << i;
    EXPECT_GE(planned.speed[i], 0.0) << i;
    if (planned.stop[i]) {
      EXPECT_EQ(planned.speed[i], 0.0) << i;
    }
    if (i + 1 == n) continue;
    const double a = std::min(whole.accel_cap[i], whole.accel_cap[i + 1]);
    const double dv2 = planned.speed[i + 1] * planned.speed[i + 1] - planned.speed[i] * planned.speed[i];
    EXPECT_LE(std::abs(dv2), 2.0 * a * (planned.s[i + 1] - planned.s[i]) * (1 + 1e-12) + 1e-12) << i;
    EXPECT_GT(planned.speed[i] + planned.speed[i + 1], 0.0) << i;
  }
}

TEST(LookaheadProfile, EqualsTheWholePlanToTheBitWhereTheWindowHoldsTheBrakingDistance) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 6; ++trial) {
    const Generated g = random_path(rng, 12000 + 3000 * trial);
    const ProfileSamples whole = whole_plan(g.samples);
    // Unbounded, then bounded well beyond any braking distance (200²/(2·100) = 200 path units).
    for (const double length : {std::numeric_limits<double>::infinity(), 600.0}) {
      ProfileSamples windowed = g.samples;
      const long binding = plan_speeds_lookahead(windowed, g.move, settings(length, 400, 100000));
      EXPECT_EQ(binding, 0);
      for (std::size_t i = 0; i < whole.size(); ++i) {
        ASSERT_EQ(windowed.speed[i], whole.speed[i]) << "trial " << trial << " sample " << i;
        ASSERT_EQ(windowed.speed_cap[i], whole.speed_cap[i]) << i;
        ASSERT_EQ(windowed.accel_cap[i], whole.accel_cap[i]) << i;
      }
    }
  }
}

TEST(LookaheadProfile, ABindingWindowKeepsEveryLimitAndIsNeverFaster) {
  std::mt19937_64 rng(43);
  for (int trial = 0; trial < 12; ++trial) {
    const Generated g = random_path(rng, 8000);
    const ProfileSamples whole = whole_plan(g.samples);
    std::uniform_real_distribution<double> length(1.0, 150.0);
    std::uniform_int_distribution<int> moves(1, 60);
    std::uniform_int_distribution<std::size_t> samples(2, 300);
    ProfileSamples windowed = g.samples;
    // Every third trial the tightest window: full at every sample, so it is planned at every push.
    const bool tightest = trial % 3 == 0;
    plan_speeds_lookahead(windowed, g.move,
                          tightest ? settings(1.0, 1, 2) : settings(length(rng), moves(rng), samples(rng)));
    expect_within_limits(windowed, whole);
    for (std::size_t i = 0; i < whole.size(); ++i) EXPECT_LE(windowed.speed[i], whole.speed[i]) << i;
  }
}

TEST(LookaheadProfile, ALongStraightBeforeASharpCornerBindsAndStillStopsInTime) {
  // 3000 units at a cap of 200 with 100 units/s² of acceleration: braking takes 200 units, more than the
  // window of 40 units (4 reaches of the filter) holds; the corner is a stop.
  ProfileSamples p;
  const std::size_t n = 3001;
  p.resize(n);
  std::vector<int> move(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    p.s[i] = static_cast<double>(i);
    p.speed_cap[i] = i == 0 || i + 1 == n ? 0.0 : kFastest;
    p.accel_cap[i] = 100.0;
    p.stop[i] = i == 0 || i + 1 == n;
    p.hold_s[i] = p.stop[i] ? kFilterS : 0.0;
  }
  const ProfileSamples whole = whole_plan(p);
  ProfileSamples windowed = p;
  const long binding = plan_speeds_lookahead(windowed, move, settings(40.0, 1000, 100000));
  EXPECT_GT(binding, 0);
  expect_within_limits(windowed, whole);
  const double fastest = *std::max_element(windowed.speed.begin(), windowed.speed.end());
  const double whole_fastest = *std::max_element(whole.speed.begin(), whole.speed.end());
  EXPECT_EQ(whole_fastest, kFastest);
  // The window's speed is what stops within it: v² ≤ 2·a·L, with L the window of 40 units (and the
  // sixteenth it may overshoot by before it is planned again).
  EXPECT_LE(fastest, std::sqrt(2.0 * 100.0 * 40.0 * (1.0 + 1.0 / 16)) * (1 + 1e-12));
  EXPECT_GT(fastest, 0.25 * std::sqrt(2.0 * 100.0 * 40.0));
  EXPECT_GT(time_profile(windowed).end_time_s, time_profile(whole).end_time_s);
}

TEST(LookaheadProfile, MemoryIsTheWindowsNotThePaths) {
  std::mt19937_64 rng(47);
  std::size_t peak[2] = {0, 0};
  const std::size_t lengths[2] = {20000, 200000};
  for (int k = 0; k < 2; ++k) {
    const Generated g = random_path(rng, lengths[k]);
    LookaheadProfile profile(settings(600.0, 400, 100000));
    for (std::size_t i = 0; i < g.samples.size(); ++i) {
      profile.push(RawSample{g.samples.s[i], g.samples.speed_cap[i], g.samples.accel_cap[i],
                             g.samples.hold_s[i], g.samples.stop[i] != 0, g.move[i]});
      profile.clear_planned();
    }
    profile.finish();
    peak[k] = profile.peak_window_samples();
  }
  EXPECT_LT(peak[0], lengths[0] / 2);
  EXPECT_LE(static_cast<double>(peak[1]), 1.1 * static_cast<double>(peak[0]));
}

}  // namespace
}  // namespace pkm::planning
