#include "calibration/tool_sensitivity.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <optional>

namespace pkm::calibration {

namespace {

Result<std::vector<Eigen::Vector3d>> tool_points(const Mechanism& model, const ParameterLayout& layout,
                                                 const Eigen::VectorXd& parameters,
                                                 const std::vector<ActuatorVector>& readings,
                                                 const std::vector<Pose>& guesses, const FkOptions& fk) {
  auto mechanism = mechanism_with_parameters(model, layout, parameters);
  if (!mechanism) return mechanism.error();
  std::vector<Eigen::Vector3d> points;
  points.reserve(readings.size());
  for (std::size_t p = 0; p < readings.size(); ++p) {
    auto solution = (*mechanism)->forward(readings[p], guesses[p], fk);
    if (!solution) {
      return make_error(solution.error().code, fmt::format("pose {}: {}", p + 1, solution.error().message));
    }
    points.push_back(solution->pose.position_mm);
  }
  return points;
}

}  // namespace

Result<std::vector<ToolSensitivity>> tool_point_sensitivities(const Mechanism& model,
                                                              const ParameterLayout& layout,
                                                              const Eigen::VectorXd& parameters,
                                                              const std::vector<Pose>& poses,
                                                              const ResidualOptions& options) {
  auto base = mechanism_with_parameters(model, layout, parameters);
  if (!base) return base.error();
  std::vector<ActuatorVector> readings;
  readings.reserve(poses.size());
  for (std::size_t p = 0; p < poses.size(); ++p) {
    auto r = (*base)->inverse(poses[p]);
    if (!r) return make_error(r.error().code, fmt::format("pose {}: {}", p + 1, r.error().message));
    readings.push_back(*r);
  }
  const int n = layout.size();
  std::vector<ToolSensitivity> g(poses.size(), ToolSensitivity::Zero(3, n));
  std::vector<std::optional<Error>> errors(static_cast<std::size_t>(n));
  tbb::parallel_for(0, n, [&](int i) {
    const double step = options.derivative_step_mm * layout.scale[i];
    Eigen::VectorXd stepped = parameters;
    stepped[i] += step;
    auto plus = tool_points(model, layout, stepped, readings, poses, options.fk);
    stepped[i] = parameters[i] - step;
    auto minus = plus ? tool_points(model, layout, stepped, readings, poses, options.fk) : plus;
    if (!plus || !minus) {
      errors[static_cast<std::size_t>(i)] = !plus ? plus.error() : minus.error();
      return;
    }
    for (std::size_t p = 0; p < poses.size(); ++p) g[p].col(i) = ((*plus)[p] - (*minus)[p]) / (2.0 * step);
  });
  for (int i = 0; i < n; ++i) {
    if (const auto& e = errors[static_cast<std::size_t>(i)]) {
      return make_error(e->code, fmt::format("the tool point's derivative by {}: {}",
                                             layout.names[static_cast<std::size_t>(i)], e->message));
    }
  }
  return g;
}

}  // namespace pkm::calibration
