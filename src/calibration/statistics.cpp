#include "calibration/statistics.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::calibration {

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double at = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(at));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = at - static_cast<double>(below);
  if (values[above] == values[below]) return values[below];  // also for infinite values
  return values[below] + fraction * (values[above] - values[below]);
}

double root_mean_square(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace pkm::calibration
