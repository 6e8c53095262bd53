// Corner blends on generated pairs of moves: lines, arcs and helices, with and without a turning tool, from
// micrometre to 50 mm long, at every angle up to a reversal. Whatever the pair, a blend either stays within
// the tolerance of both moves, takes at most half of each and is followed at the planned speed (its
// arc-length map is monotone and true), or the corner becomes an exact stop.
#include "path/corner_blend.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "path_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

/// The path of two moves joined at one corner, blended with `tolerance_mm`.
path::Path blended_pair(const path::Curve& a, const path::Curve& b, double tolerance_mm) {
  path::Path p;
  p.curves = {a, b};
  for (int k = 0; k < 2; ++k) {
    path::Segment seg;
    seg.curve_a = k;
    seg.length = p.curves[k].param_length;
    seg.speed_limit = 10.0;
    seg.line = k + 1;
    seg.move = k;
    p.segments.push_back(seg);
  }
  p.segments.back().stop_after = true;
  path::blend_corners(p, tolerance_mm);
  double s = 0.0;
  for (path::Segment& seg : p.segments) {
    seg.s_start = s;
    s += seg.length;
  }
  return p;
}

struct BlendCheck {
  bool blended = false;
  double worst_deviation_mm = 0.0;
  double fastest_ratio = 0.0;  ///< largest |dP/ds| over the blend (1: followed at the planned speed)
  double slowest_ratio = 1e300;
};

BlendCheck check_pair(const path::Curve& a, const path::Curve& b, double tolerance_mm,
                      const std::string& label) {
  const path::Path p = blended_pair(a, b, tolerance_mm);
  BlendCheck check;
  for (int k = 0; k < static_cast<int>(p.segments.size()); ++k) {
    const path::Segment& seg = p.segments[k];
    if (!seg.is_blend()) continue;
    check.blended = true;
    EXPECT_GE(seg.fa0, 0.5 - 1e-12) << label;
    EXPECT_LE(seg.fb1, 0.5 + 1e-12) << label;
    constexpr int samples = 100;
    Eigen::Vector3d previous = p.evaluate(k, seg.s_start).position_mm;
    for (int i = 1; i <= samples; ++i) {
      const Eigen::Vector3d q = p.evaluate(k, seg.s_start + seg.length * i / samples).position_mm;
      const double d =
          std::min(test::distance_to_programmed_move(a, q), test::distance_to_programmed_move(b, q));
      check.worst_deviation_mm = std::max(check.worst_deviation_mm, d);
      const double ratio = (q - previous).norm() / (seg.length / samples);
      check.fastest_ratio = std::max(check.fastest_ratio, ratio);
      check.slowest_ratio = std::min(check.slowest_ratio, ratio);
      previous = q;
    }
  }
  if (!check.blended) {
    // No blend: an exact stop at the corner (unless the moves join tangentially).
    const Eigen::Vector3d t1 = a.velocity(1.0).normalized(), t2 = b.velocity(0.0).normalized();
    if (std::acos(std::clamp(t1.dot(t2), -1.0, 1.0)) > 1e-7) {
      EXPECT_TRUE(p.segments.front().stop_after) << label << ": a corner with neither blend nor stop";
    }
  }
  EXPECT_LE(check.worst_deviation_mm, tolerance_mm * 1.001 + 1e-12) << label;
  return check;
}

Eigen::Quaterniond random_rotation(std::mt19937_64& rng, double max_deg) {
  const Eigen::Vector3d axis = Eigen::Vector3d::Random().normalized();
  return Eigen::Quaterniond(
      Eigen::AngleAxisd(test::uniform(rng, -max_deg, max_deg) * std::numbers::pi / 180, axis));
}

/// A random line or helix from `start`, heading roughly along `direction`, `length` mm long.
path::Curve random_move(std::mt19937_64& rng, const Eigen::Vector3d& start, const Eigen::Vector3d& direction,
                        double length, const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1) {
  if (test::uniform(rng, 0, 1) < 0.5) return path::make_line(start, start + length * direction, q0, q1);
  // An arc tangent to `direction` at its start, of radius 0.3…5× its length, in a random plane through it.
  Eigen::Vector3d normal = direction.cross(Eigen::Vector3d::Random()).normalized();
  const double radius = length * test::uniform(rng, 0.3, 5.0);
  const double sweep = std::min(length / radius, 1.9 * std::numbers::pi);
  const Eigen::Vector3d centre = start + radius * normal.cross(direction).normalized();
  const Eigen::Vector3d u = (start - centre).normalized(), v = normal.cross(u);
  Eigen::Vector3d end = centre + radius * (std::cos(sweep) * u + std::sin(sweep) * v);
  end += test::uniform(rng, -0.3, 0.3) * length * normal;  // a helix now and then
  return path::make_helix(start, end, centre, normal, 1, q0, q1);
}

TEST(CornerBlend, TwoLinesAtEveryAngleBlendOrStop) {
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (double length : {1e-3, 0.05, 0.5, 10.0}) {
    for (double deg :
         {1e-6, 0.01, 1.0, 30.0, 90.0, 150.0, 170.0, 175.0, 178.0, 179.0, 179.9, 179.999, 180.0}) {
      const double th = deg * std::numbers::pi / 180.0;
      const Eigen::Vector3d a(100, 50, 700), b = a + Eigen::Vector3d(length, 0, 0);
      const Eigen::Vector3d c = b + length * Eigen::Vector3d(std::cos(th), std::sin(th), 0);
      const std::string label = "length " + std::to_string(length) + " turn " + std::to_string(deg);
      const BlendCheck check =
          check_pair(path::make_line(a, b, q, q), path::make_line(b, c, q, q), 0.01, label);
      if (deg >= 179.0) {
        EXPECT_FALSE(check.blended) << label << ": a reversal must stop";
      } else if (deg >= 0.01 && deg <= 170.0) {
        EXPECT_TRUE(check.blended) << label;
      }
      if (check.blended) {
        EXPECT_LT(check.fastest_ratio, 1.05) << label << ": followed faster than planned";
        EXPECT_GT(check.slowest_ratio, 0.5) << label;
      }
    }
  }
}

TEST(CornerBlend, RandomPairsOfMovesStayWithinTheTolerance) {
  std::mt19937_64 rng(12);
  int blended = 0, stopped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double tolerance = std::pow(10.0, test::uniform(rng, -3.5, -1.0));
    const double la = std::pow(10.0, test::uniform(rng, -3.0, 1.7));
    const double lb = std::pow(10.0, test::uniform(rng, -3.0, 1.7));
    const Eigen::Vector3d d1 = Eigen::Vector3d::Random().normalized();
    // Turn angles spread over the whole range, crowded near 0 and near a reversal.
    const double turn = trial % 3 == 0 ? std::numbers::pi * (1.0 - std::pow(10.0, test::uniform(rng, -5, 0)))
                                       : std::numbers::pi * std::pow(10.0, test::uniform(rng, -6, 0));
    const Eigen::Vector3d side = d1.cross(Eigen::Vector3d::Random()).normalized();
    const Eigen::Vector3d d2 = std::cos(turn) * d1 + std::sin(turn) * side;
    const bool turning = trial % 2 == 1;  // orientation changes along the moves
    const Eigen::Quaterniond q0 = turning ? random_rotation(rng, 10) : Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond q1 = turning ? random_rotation(rng, 10) : q0;
    const Eigen::Quaterniond q2 = turning ? random_rotation(rng, 10) : q0;
    const Eigen::Vector3d start(test::uniform(rng, -50, 50), test::uniform(rng, -50, 50), 700);
    path::Curve a = path::make_line(start, start + la * d1, q0, q1);
    if (trial % 4 == 1) a = random_move(rng, start, d1, la, q0, q1);
    path::Curve b = random_move(rng, a.end_mm, d2, lb, q1, q2);
    if (trial % 5 == 0) {  // a tool 50…150 mm long, turning with the platform (G43 on a 5-axis move)
      a.tool_length_mm = b.tool_length_mm = test::uniform(rng, 50, 150);
    }
    const std::string label = "trial " + std::to_string(trial);
    const BlendCheck check = check_pair(a, b, tolerance, label);
    if (check.blended) {
      ++blended;
      EXPECT_LT(check.fastest_ratio, 1.1) << label;
    } else {
      ++stopped;
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(blended, 100);
  EXPECT_GT(stopped, 20);
}

TEST(CornerBlend, ArcLengthMapOfASharpBlendStaysOnTheBlend) {
  // 171°: the sharpest corners that still blend have the least regular cross-fade.
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const double th = 171.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d a(0, 0, 0), b(0.5, 0, 0),
      c = b + 0.5 * Eigen::Vector3d(std::cos(th), std::sin(th), 0);
  const path::Path p = blended_pair(path::make_line(a, b, q, q), path::make_line(b, c, q, q), 0.01);
  ASSERT_EQ(p.segments.size(), 3u);
  ASSERT_TRUE(p.segments[1].is_blend());
  const path::BlendTable& table = p.blend_tables.front();
  for (int k = 1; k < path::kBlendKnots; ++k) EXPECT_GT(table.s[k], table.s[k - 1]);
  EXPECT_EQ(table.s.front(), 0.0);
  EXPECT_EQ(table.s.back(), 1.0);
  for (int i = 0; i <= 1000; ++i) {
    const double s = p.segments[1].s_start + p.segments[1].length * i / 1000.0;
    EXPECT_LT((p.evaluate(1, s).position_mm - b).norm(), 0.26) << i;
  }
}

TEST(CornerBlend, CollinearMovesNeedNeitherBlendNorStop) {
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d a(0, 0, 0), b(1e-3, 0, 0), c(5, 0, 0);
  const path::Path p = blended_pair(path::make_line(a, b, q, q), path::make_line(b, c, q, q), 0.01);
  EXPECT_EQ(p.segments.size(), 2u);
  EXPECT_FALSE(p.segments.front().stop_after);
}

TEST(CornerBlend, ToleranceZeroStopsAtEveryCorner) {
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(1, 1, 0);
  const path::Path p = blended_pair(path::make_line(a, b, q, q), path::make_line(b, c, q, q), 0.0);
  EXPECT_EQ(p.segments.size(), 2u);
  EXPECT_TRUE(p.segments.front().stop_after);
}

TEST(CornerBlend, VelocityIsTheDerivativeOfPosition) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d d = Eigen::Vector3d::Random().normalized();
    path::Curve c = random_move(rng, Eigen::Vector3d(10, 20, 700), d, test::uniform(rng, 0.1, 30.0),
                                random_rotation(rng, 20), random_rotation(rng, 20));
    c.tool_length_mm = trial % 2 ? 100.0 : 0.0;
    for (double f : {0.1, 0.5, 0.9}) {
      const double h = 1e-6;
      const Eigen::Vector3d numeric = (c.position(f + h) - c.position(f - h)) / (2 * h);
      EXPECT_LT((c.velocity(f) - numeric).norm(), 1e-5 * (1.0 + numeric.norm())) << trial << " f " << f;
    }
  }
}

}  // namespace
}  // namespace pkm
