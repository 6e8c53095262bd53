#include "core/duration_histogram.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace pkm {

namespace {
constexpr int kExactBits = DurationHistogram::kSubBucketBits + 1;  // below 2^6 = 64 ns: one bucket per ns
}  // namespace

std::size_t DurationHistogram::bucket_of(std::int64_t duration_ns) noexcept {
  const auto value = static_cast<std::uint64_t>(std::max<std::int64_t>(duration_ns, 0));
  const int width = std::bit_width(value);
  const int shift = std::max(0, width - kExactBits);
  if (shift > kLargestShift) return kBuckets - 1;
  // Within doubling `shift` the top six bits (32…63) pick the bucket: contiguous with the exact ones below.
  return (static_cast<std::size_t>(shift) << kSubBucketBits) + static_cast<std::size_t>(value >> shift);
}

std::int64_t DurationHistogram::bucket_upper_ns(std::size_t bucket) noexcept {
  constexpr std::size_t exact = std::size_t{1} << kExactBits;
  if (bucket < exact) return static_cast<std::int64_t>(bucket);
  const std::size_t shift = (bucket >> kSubBucketBits) - 1;
  const std::size_t mantissa = bucket - (shift << kSubBucketBits);
  return static_cast<std::int64_t>(((mantissa + 1) << shift) - 1);
}

void DurationHistogram::add(std::int64_t duration_ns) noexcept {
  ++counts_[bucket_of(duration_ns)];
  max_ns_ = count_ ? std::max(max_ns_, duration_ns) : duration_ns;
  min_ns_ = count_ ? std::min(min_ns_, duration_ns) : duration_ns;
  sum_ns_ += static_cast<double>(duration_ns);
  if (budget_ns_ > 0 && duration_ns > budget_ns_) ++over_budget_;
  ++count_;
}

void DurationHistogram::clear() noexcept {
  counts_.fill(0);
  count_ = 0;
  over_budget_ = 0;
  sum_ns_ = 0.0;
  max_ns_ = min_ns_ = 0;
}

double DurationHistogram::percentile_us(double fraction) const {
  if (count_ == 0) return 0.0;
  const auto wanted = std::max<long>(
      1, static_cast<long>(std::ceil(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(count_))));
  long seen = 0;
  for (std::size_t b = 0; b < kBuckets; ++b) {
    seen += static_cast<long>(counts_[b]);
    if (seen < wanted) continue;
    if (b == kBuckets - 1) break;  // beyond the range: the largest sample is the only known edge
    return static_cast<double>(std::min(bucket_upper_ns(b), max_ns_)) * 1e-3;
  }
  return max_us();
}

DurationDistribution DurationHistogram::distribution() const {
  DurationDistribution d;
  d.count = count_;
  d.p50_us = percentile_us(0.5);
  d.p99_us = percentile_us(0.99);
  d.p99_9_us = percentile_us(0.999);
  d.max_us = max_us();
  d.mean_us = mean_us();
  d.min_us = min_us();
  d.over_budget = over_budget_;
  return d;
}

}  // namespace pkm
