#include "calibration/parameter_jacobian.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <optional>

namespace pkm::calibration {

namespace {

Result<Eigen::VectorXd> weighted_at(const ResidualModel& residuals, const Mechanism& model,
                                    const ParameterLayout& layout, const Eigen::VectorXd& parameters,
                                    std::vector<Pose> poses) {
  auto mechanism = mechanism_with_parameters(model, layout, parameters);
  if (!mechanism) return mechanism.error();
  Eigen::VectorXd raw, weighted;
  if (auto ok = residuals.evaluate(**mechanism, poses, raw, &weighted); !ok) return ok.error();
  return weighted;
}

}  // namespace

Result<Eigen::MatrixXd> residual_jacobian(const ResidualModel& residuals, const Mechanism& model,
                                          const ParameterLayout& layout, const Eigen::VectorXd& parameters,
                                          const std::vector<Pose>& poses) {
  const int n = layout.size();
  const double h = residuals.options().derivative_step_mm;
  Eigen::MatrixXd jacobian(residuals.rows(), n);
  std::vector<std::optional<Error>> errors(static_cast<std::size_t>(n));
  tbb::parallel_for(0, n, [&](int i) {
    Eigen::VectorXd stepped = parameters;
    const double step = h * layout.scale[i];
    stepped[i] = parameters[i] + step;
    auto plus = weighted_at(residuals, model, layout, stepped, poses);
    stepped[i] = parameters[i] - step;
    auto minus = plus ? weighted_at(residuals, model, layout, stepped, poses) : plus;
    if (!plus || !minus) {
      errors[static_cast<std::size_t>(i)] = !plus ? plus.error() : minus.error();
      return;
    }
    jacobian.col(i) = (*plus - *minus) / (2.0 * h);
  });
  for (int i = 0; i < n; ++i) {
    if (const auto& e = errors[static_cast<std::size_t>(i)]) {
      return make_error(e->code, fmt::format("the derivative by {}: {}",
                                             layout.names[static_cast<std::size_t>(i)], e->message));
    }
  }
  return jacobian;
}

}  // namespace pkm::calibration
