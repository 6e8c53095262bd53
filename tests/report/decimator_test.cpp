// The report's decimation (report/decimator.hpp): peaks survive, short series are kept whole, gaps stay gaps.
#include "report/decimator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace pkm {
namespace {

TEST(MinMaxDecimator, ShortSeriesAreKeptWhole) {
  report::MinMaxDecimator d(1, 100, 2000);
  for (int i = 0; i < 100; ++i) {
    const double v = i * 0.5;
    d.add(i * 0.001, i * 2.0, &v);
  }
  d.finish();
  ASSERT_EQ(d.time_s().size(), 100u);
  EXPECT_DOUBLE_EQ(d.values(0)[37], 18.5);
  EXPECT_DOUBLE_EQ(d.s_mm()[37], 74.0);
}

TEST(MinMaxDecimator, EveryBucketKeepsItsExtremesInTheOrderTheyOccurred) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const long n = 1'000'003;
  std::vector<double> a(n), b(n);
  for (long i = 0; i < n; ++i) {
    a[i] = std::sin(i * 1e-4) + 0.01 * noise(rng);
    b[i] = -a[i];
  }
  a[123456] = 50.0;  // a one-sample spike
  b[654321] = -70.0;
  report::MinMaxDecimator d(2, n, 1000);
  for (long i = 0; i < n; ++i) {
    const double v[2] = {a[i], b[i]};
    d.add(i * 1e-3, std::numeric_limits<double>::quiet_NaN(), v);
  }
  d.finish();
  EXPECT_LE(d.time_s().size(), 2u * 1001u);
  EXPECT_GE(d.time_s().size(), 2u * 999u);
  EXPECT_EQ(d.samples(), n);
  // The global extremes are among the kept points, and so is every bucket's.
  EXPECT_DOUBLE_EQ(*std::max_element(d.values(0).begin(), d.values(0).end()), 50.0);
  EXPECT_DOUBLE_EQ(*std::min_element(d.values(1).begin(), d.values(1).end()), -70.0);
  EXPECT_DOUBLE_EQ(d.peak(0), 50.0);
  EXPECT_DOUBLE_EQ(d.peak(1), 70.0);
  const long bucket = (n + 999) / 1000;
  for (std::size_t k = 0; k + 1 < d.time_s().size(); k += 2) {
    const long first = static_cast<long>(k / 2) * bucket;
    const long last = std::min(n, first + bucket);
    const auto [lo, hi] = std::minmax_element(a.begin() + first, a.begin() + last);
    EXPECT_DOUBLE_EQ(std::min(d.values(0)[k], d.values(0)[k + 1]), *lo);
    EXPECT_DOUBLE_EQ(std::max(d.values(0)[k], d.values(0)[k + 1]), *hi);
    // In time order: the first kept value is the extreme that came first.
    EXPECT_EQ(d.values(0)[k] == *lo, lo - a.begin() <= hi - a.begin()) << k;
    EXPECT_DOUBLE_EQ(d.time_s()[k], first * 1e-3);
    EXPECT_DOUBLE_EQ(d.time_s()[k + 1], (last - 1) * 1e-3);
  }
}

TEST(MinMaxDecimator, GapsStayGaps) {
  report::MinMaxDecimator d(1, 10'000, 100);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 10'000; ++i) {
    const double v = i < 5000 ? nan : 1.0;
    d.add(i, i, &v);
  }
  d.finish();
  EXPECT_TRUE(std::isnan(d.values(0).front()));
  EXPECT_DOUBLE_EQ(d.values(0).back(), 1.0);
}

TEST(ReportJsonNumbers, RoundToSignificantDigitsAndNullForNonFinite) {
  EXPECT_TRUE(report::json_number(std::numeric_limits<double>::quiet_NaN()).is_null());
  EXPECT_TRUE(report::json_number(std::numeric_limits<double>::infinity()).is_null());
  EXPECT_DOUBLE_EQ(report::json_number(623.79117284, 6).get<double>(), 623.791);
  EXPECT_DOUBLE_EQ(report::json_number(-4.9167612e-4, 3).get<double>(), -4.92e-4);
  EXPECT_EQ(report::json_number(0.0).get<double>(), 0.0);
}

}  // namespace
}  // namespace pkm
