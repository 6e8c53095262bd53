// The fixed histogram behind the period-time and lateness distributions (core/duration_histogram.hpp).
#include "core/duration_histogram.hpp"

#include <gtest/gtest.h>

namespace pkm {
namespace {

TEST(DurationHistogram, BucketsAreContiguousAndWithinThreePercent) {
  std::size_t previous = 0;
  for (std::int64_t ns = 0; ns < 1'000'000; ns += ns < 4096 ? 1 : 97) {
    const std::size_t bucket = DurationHistogram::bucket_of(ns);
    EXPECT_GE(bucket, previous) << ns;  // monotone in the duration
    EXPECT_LE(bucket, previous + 1) << ns;
    previous = bucket;
    const std::int64_t upper = DurationHistogram::bucket_upper_ns(bucket);
    EXPECT_GE(upper, ns);
    EXPECT_LE(static_cast<double>(upper - ns), static_cast<double>(ns) / 32.0 + 1e-9) << ns;
  }
  EXPECT_EQ(DurationHistogram::bucket_of(63), 63u);  // exact below 64 ns
  EXPECT_EQ(DurationHistogram::bucket_of(-5), 0u);
  EXPECT_EQ(DurationHistogram::bucket_of(std::int64_t{1} << 62), DurationHistogram::kBuckets - 1);
}

TEST(DurationHistogram, PercentilesAreOrderedAndNeverAboveTheLargest) {
  DurationHistogram histogram(10'000);
  EXPECT_EQ(histogram.percentile_us(0.99), 0.0);
  for (int k = 0; k < 1000; ++k) histogram.add(1000 + k);  // 1.000 … 1.999 µs
  histogram.add(250'000);                                  // one 250 µs outlier
  const DurationDistribution d = histogram.distribution();
  EXPECT_EQ(d.count, 1001);
  EXPECT_EQ(d.over_budget, 1);
  EXPECT_DOUBLE_EQ(d.max_us, 250.0);
  EXPECT_DOUBLE_EQ(d.min_us, 1.0);
  EXPECT_NEAR(d.p50_us, 1.5, 1.5 / 32);
  EXPECT_NEAR(d.p99_us, 1.99, 1.99 / 32);
  EXPECT_NEAR(d.p99_9_us, 2.0, 2.0 / 32);  // the 1000th of 1001: below the outlier
  EXPECT_LE(d.p50_us, d.p99_us);
  EXPECT_LE(d.p99_us, d.p99_9_us);
  EXPECT_LE(d.p99_9_us, d.max_us);
  EXPECT_DOUBLE_EQ(histogram.percentile_us(1.0), 250.0);
  histogram.clear();
  EXPECT_EQ(histogram.count(), 0);
  EXPECT_EQ(histogram.max_us(), 0.0);
}

TEST(DurationHistogram, DurationsBeyondTheRangeKeepTheirMaximum) {
  DurationHistogram histogram;
  histogram.add(std::int64_t{1} << 40);  // 18 minutes
  EXPECT_DOUBLE_EQ(histogram.max_us(), static_cast<double>(std::int64_t{1} << 40) * 1e-3);
  EXPECT_DOUBLE_EQ(histogram.percentile_us(0.5), histogram.max_us());
  EXPECT_EQ(histogram.over_budget(), 0);  // no budget: nothing counted over it
}

}  // namespace
}  // namespace pkm
