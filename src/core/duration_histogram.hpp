#pragma once
// The distribution of many short durations (a servo period's compute time, a wake-up's lateness), kept in a
// fixed histogram inside the object: recording one costs a few instructions, never allocates and touches one
// counter, so measuring a real-time loop does not perturb it, and p99.9 needs no memory per sample.
//
// Buckets are log-linear (as HDR histograms): one per nanosecond below 64 ns, then 32 per doubling, so that a
// percentile is within 1/32 (3 %) of the true value at any scale, from nanoseconds to minutes. A percentile
// is the upper edge of its bucket, never above the largest sample. Durations beyond the last bucket (2^38 ns,
// 4.6 min) are counted in it; the largest and the smallest sample and the sum are kept exactly.
#include <array>
#include <cstdint>

namespace pkm {

/// What a run reports of a DurationHistogram, in µs.
struct DurationDistribution {
  long count = 0;
  double p50_us = 0.0, p99_us = 0.0, p99_9_us = 0.0, max_us = 0.0;
  double mean_us = 0.0, min_us = 0.0;
  long over_budget = 0;  ///< samples longer than the histogram's budget
};

class DurationHistogram {
 public:
  static constexpr int kSubBucketBits = 5;  ///< 32 buckets per doubling
  static constexpr int kLargestShift = 32;  ///< the last doubling starts at 2^37 ns
  static constexpr std::size_t kBuckets = (kLargestShift + 2) << kSubBucketBits;

  /// `budget_ns`: samples above it are counted (over_budget); 0 counts none.
  explicit DurationHistogram(std::int64_t budget_ns = 0) noexcept : budget_ns_(budget_ns) {}

  void add(std::int64_t duration_ns) noexcept;
  void clear() noexcept;

  long count() const { return count_; }
  long over_budget() const { return over_budget_; }
  std::int64_t budget_ns() const { return budget_ns_; }
  double max_us() const { return count_ ? static_cast<double>(max_ns_) * 1e-3 : 0.0; }
  double min_us() const { return count_ ? static_cast<double>(min_ns_) * 1e-3 : 0.0; }
  double mean_us() const { return count_ ? sum_ns_ / static_cast<double>(count_) * 1e-3 : 0.0; }
  /// The duration that `fraction` (0…1) of the samples did not exceed, µs (0 without samples).
  double percentile_us(double fraction) const;
  DurationDistribution distribution() const;

  /// The bucket of a duration, and the largest duration in a bucket (exposed for the tests).
  static std::size_t bucket_of(std::int64_t duration_ns) noexcept;
  static std::int64_t bucket_upper_ns(std::size_t bucket) noexcept;

 private:
  std::array<std::uint64_t, kBuckets> counts_{};
  std::int64_t budget_ns_ = 0;
  long count_ = 0;
  long over_budget_ = 0;
  double sum_ns_ = 0.0;
  std::int64_t max_ns_ = 0, min_ns_ = 0;
};

}  // namespace pkm
