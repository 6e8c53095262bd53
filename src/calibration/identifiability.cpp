#include "calibration/identifiability.hpp"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pkm::calibration {

namespace {

// The strut all named components belong to, when every one of them is in a per-strut group (rows = actuators)
// and in the same row: −1 otherwise.
int common_strut(const std::vector<int>& indices, const ParameterLayout& layout) {
  int strut = -1;
  for (int i : indices) {
    const std::size_t k = static_cast<std::size_t>(i);
    int rows = 0;
    for (const GeometryGroup& g : layout.groups) {
      if (g.key == layout.group_keys[k]) rows = g.rows;
    }
    if (rows != layout.actuator_count) return -1;
    if (strut >= 0 && strut != layout.rows[k]) return -1;
    strut = layout.rows[k];
  }
  return strut;
}

std::string combination_list(const std::vector<ParameterCombination>& combinations, std::size_t shown) {
  std::string text;
  for (std::size_t i = 0; i < combinations.size() && i < shown; ++i) {
    if (!text.empty()) text += "; ";
    text += combinations[i].description;
  }
  if (combinations.size() > shown) text += fmt::format("; … ({} more)", combinations.size() - shown);
  return text;
}

}  // namespace

ParameterCombination describe_combination(const Eigen::VectorXd& direction, double relative_singular_value,
                                          const ParameterLayout& layout, int named_components) {
  ParameterCombination c;
  c.relative_singular_value = relative_singular_value;
  std::vector<int> order(static_cast<std::size_t>(direction.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return std::abs(direction[a]) > std::abs(direction[b]); });
  // A singular vector's sign is arbitrary: show the largest component positive.
  const double sign = order.empty() || direction[order[0]] >= 0.0 ? 1.0 : -1.0;
  const double largest = order.empty() ? 0.0 : std::abs(direction[order[0]]);
  std::vector<int> named;
  for (int i : order) {
    if (static_cast<int>(named.size()) >= named_components || std::abs(direction[i]) < 0.25 * largest) break;
    named.push_back(i);
    c.components.emplace_back(layout.names[static_cast<std::size_t>(i)], sign * direction[i]);
  }
  for (const auto& [name, value] : c.components) {
    if (!c.description.empty()) c.description += ' ';
    c.description += fmt::format("{}{:.2f} {}", value < 0.0 ? "−" : "+", std::abs(value), name);
  }
  if (const int strut = common_strut(named, layout); strut >= 0 && named.size() > 1) {
    c.description += fmt::format(" (strut {})", strut + 1);
  }
  return c;
}

Identifiability analyse_identifiability(const Eigen::MatrixXd& scaled_jacobian, const ParameterLayout& layout,
                                        const IdentifiabilityOptions& options) {
  Identifiability a;
  a.parameters = static_cast<int>(scaled_jacobian.cols());
  a.equations = static_cast<int>(scaled_jacobian.rows());
  const int n = a.parameters;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(scaled_jacobian, Eigen::ComputeFullV);
  a.singular_values = Eigen::VectorXd::Zero(n);
  a.singular_values.head(svd.singularValues().size()) = svd.singularValues();
  a.right_vectors = svd.matrixV();
  const double largest = n > 0 ? a.singular_values[0] : 0.0;
  a.rank = 0;
  while (a.rank < n && largest > 0.0 && a.singular_values[a.rank] >= options.relative_threshold * largest)
    ++a.rank;
  const double infinity = std::numeric_limits<double>::infinity();
  a.condition_number =
      n > 0 && a.singular_values[n - 1] > 0.0 ? largest / a.singular_values[n - 1] : infinity;
  a.identifiable_condition_number = a.rank > 0 ? largest / a.singular_values[a.rank - 1] : infinity;

  for (int i = a.rank; i < n; ++i) {
    a.unidentifiable.push_back(describe_combination(a.right_vectors.col(i),
                                                    largest > 0.0 ? a.singular_values[i] / largest : 0.0,
                                                    layout, options.named_components));
  }
  for (int i = a.rank - 1; i >= 0 && a.rank - 1 - i < options.weakest_named; --i) {
    a.weakest.push_back(describe_combination(a.right_vectors.col(i), a.singular_values[i] / largest, layout,
                                             options.named_components));
  }

  // Σ_u = V_k·diag(1/σ²)·V_kᵀ over the scaled parameters u = θ/s, so Σ_θ = S·Σ_u·S.
  const Eigen::MatrixXd vk = a.right_vectors.leftCols(a.rank);
  const Eigen::VectorXd inverse_squares = a.singular_values.head(a.rank).array().square().inverse().matrix();
  const Eigen::MatrixXd scaled_covariance = vk * inverse_squares.asDiagonal() * vk.transpose();
  a.covariance = layout.scale.asDiagonal() * scaled_covariance * layout.scale.asDiagonal();
  a.standard_deviation = a.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();

  if (a.rank < n) {
    a.warnings.push_back(
        fmt::format("{} of {} parameter combinations cannot be identified from this plan (singular value "
                    "below {:.0e} of the "
                    "largest); they stay at the drawing values: {}",
                    n - a.rank, n, options.relative_threshold, combination_list(a.unidentifiable, 6)));
  }
  a.badly_conditioned = a.identifiable_condition_number > options.warn_condition_number;
  if (a.badly_conditioned) {
    a.warnings.push_back(
        fmt::format("the plan is badly conditioned: condition number {:.3g} of the identification Jacobian "
                    "exceeds {:.3g}; "
                    "the weakest combination ({}) is determined {:.3g} times worse than the strongest",
                    a.identifiable_condition_number, options.warn_condition_number,
                    a.weakest.empty() ? std::string("-") : a.weakest.front().description,
                    a.identifiable_condition_number));
  }
  return a;
}

}  // namespace pkm::calibration
