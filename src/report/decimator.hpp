#pragma once
// Decimation of long time series for the report's plots (the eye cannot see more points than a plot has
// pixels): samples fall into buckets of equal count, and each bucket gives two points, carrying each series'
// minimum and maximum in the order they occurred, so peaks and limit crossings survive. Short series are kept
// whole. Memory is per bucket, not per sample: a run of any length fits.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pkm::report {

class MinMaxDecimator {
 public:
  /// `series` values per sample; `expected_samples` sets the bucket size so that about `buckets` buckets
  /// result (more samples than expected just make more buckets).
  MinMaxDecimator(int series, long expected_samples, int buckets = 2000);

  /// One sample at time t (s) and path length s (mm, NaN if not known); NaN values are gaps.
  void add(double time_s, double s_mm, const double* values);
  /// Closes the last bucket; call once after the last sample.
  void finish();

  int series() const { return series_; }
  long samples() const { return samples_; }
  const std::vector<double>& time_s() const { return time_s_; }
  const std::vector<double>& s_mm() const { return s_mm_; }
  const std::vector<double>& values(int k) const { return values_[static_cast<std::size_t>(k)]; }
  /// The largest |value| of series k over every sample (not only the kept ones), 0 if none.
  double peak(int k) const { return peak_[static_cast<std::size_t>(k)]; }

 private:
  void flush();

  int series_;
  long bucket_size_;
  long samples_ = 0;
  long in_bucket_ = 0;
  double first_time_ = 0.0, last_time_ = 0.0, first_s_ = 0.0, last_s_ = 0.0;
  std::vector<double> min_, max_, peak_;
  std::vector<long> min_at_, max_at_;
  std::vector<double> time_s_, s_mm_;
  std::vector<std::vector<double>> values_;
};

/// A number for the report's JSON: NaN and infinities become null (a gap), others are rounded to
/// `digits` significant digits so that the page stays small.
nlohmann::json json_number(double value, int digits = 6);
/// An array of json_number()s.
nlohmann::json json_numbers(const std::vector<double>& values, int digits = 6);

}  // namespace pkm::report
