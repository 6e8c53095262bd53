#include "report/decimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pkm::report {

MinMaxDecimator::MinMaxDecimator(int series, long expected_samples, int buckets)
    : series_(series),
      // Two points per bucket: a bucket of one or two samples would only repeat them.
      bucket_size_(expected_samples > 2L * buckets ? (expected_samples + buckets - 1) / buckets : 1),
      min_(static_cast<std::size_t>(series)),
      max_(static_cast<std::size_t>(series)),
      peak_(static_cast<std::size_t>(series), 0.0),
      min_at_(static_cast<std::size_t>(series)),
      max_at_(static_cast<std::size_t>(series)),
      values_(static_cast<std::size_t>(series)) {}

void MinMaxDecimator::add(double time_s, double s_mm, const double* values) {
  if (in_bucket_ == 0) {
    first_time_ = time_s;
    first_s_ = s_mm;
    std::fill(min_.begin(), min_.end(), std::numeric_limits<double>::infinity());
    std::fill(max_.begin(), max_.end(), -std::numeric_limits<double>::infinity());
  }
  last_time_ = time_s;
  last_s_ = s_mm;
  for (std::size_t k = 0; k < min_.size(); ++k) {
    const double v = values[k];
    if (std::isnan(v)) continue;
    peak_[k] = std::max(peak_[k], std::abs(v));
    if (v < min_[k]) min_[k] = v, min_at_[k] = in_bucket_;
    if (v > max_[k]) max_[k] = v, max_at_[k] = in_bucket_;
  }
  ++samples_;
  if (++in_bucket_ == bucket_size_) flush();
}

void MinMaxDecimator::flush() {
  if (in_bucket_ == 0) return;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (bucket_size_ == 1) {
    time_s_.push_back(first_time_);
    s_mm_.push_back(first_s_);
    for (std::size_t k = 0; k < min_.size(); ++k)
      values_[k].push_back(std::isfinite(min_[k]) ? min_[k] : nan);
  } else {
    time_s_.push_back(first_time_);
    time_s_.push_back(last_time_);
    s_mm_.push_back(first_s_);
    s_mm_.push_back(last_s_);
    for (std::size_t k = 0; k < min_.size(); ++k) {
      const bool any = std::isfinite(min_[k]);
      const bool min_first = min_at_[k] <= max_at_[k];
      values_[k].push_back(!any ? nan : min_first ? min_[k] : max_[k]);
      values_[k].push_back(!any ? nan : min_first ? max_[k] : min_[k]);
    }
  }
  in_bucket_ = 0;
}

void MinMaxDecimator::finish() {
  flush();
}

nlohmann::json json_number(double value, int digits) {
  if (!std::isfinite(value)) return nullptr;
  if (value == 0.0) return 0;
  // Round to `digits` significant digits: the page shows at most that many, and the file stays small.
  const double magnitude = std::floor(std::log10(std::abs(value)));
  const double scale = std::pow(10.0, static_cast<double>(digits - 1) - magnitude);
  return std::round(value * scale) / scale;
}

nlohmann::json json_numbers(const std::vector<double>& values, int digits) {
  nlohmann::json out = nlohmann::json::array();
  out.get_ref<nlohmann::json::array_t&>().reserve(values.size());
  for (double v : values) out.push_back(json_number(v, digits));
  return out;
}

}  // namespace pkm::report
