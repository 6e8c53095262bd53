#pragma once
// Order statistics of trial and pose samples (calibration's summaries): linear interpolation between order
// statistics (numpy's default), so the median of an even count is the mean of the middle two.
#include <vector>

namespace pkm::calibration {

/// The q-quantile (0 ≤ q ≤ 1) of `values`; 0 for none.
double quantile(std::vector<double> values, double q);

/// Root mean square of `values`; 0 for none.
double root_mean_square(const std::vector<double>& values);

}  // namespace pkm::calibration
