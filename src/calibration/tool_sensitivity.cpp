#include "calibration/tool_sensitivity.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <optional>

namespace pkm::calibration {
namespace {

Error tool_derivative_error(const std::string& parameter, const Error& error) {
  return make_error(error.code,
                    fmt::format("the tool point's derivative by {}: {}", parameter, error.message));
}

}  // namespace

Result<ToolSensitivityModel> ToolSensitivityModel::make(const Mechanism& model, const ParameterLayout& layout,
                                                        const Eigen::VectorXd& parameters,
                                                        const ResidualOptions& options) {
  ToolSensitivityModel out;
  auto base = mechanism_with_parameters(model, layout, parameters);
  if (!base) return base.error();
  out.base_ = std::move(*base);
  out.fk_ = options.fk;
  const int n = layout.size();
  out.plus_.reserve(static_cast<std::size_t>(n));
  out.minus_.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double step = options.derivative_step_mm * layout.scale[i];
    Eigen::VectorXd stepped = parameters;
    stepped[i] += step;
    auto plus = mechanism_with_parameters(model, layout, stepped);
    if (!plus) return tool_derivative_error(layout.names[static_cast<std::size_t>(i)], plus.error());
    stepped[i] = parameters[i] - step;
    auto minus = mechanism_with_parameters(model, layout, stepped);
    if (!minus) return tool_derivative_error(layout.names[static_cast<std::size_t>(i)], minus.error());
    out.plus_.push_back(std::move(*plus));
    out.minus_.push_back(std::move(*minus));
    out.steps_.push_back(step);
    out.names_.push_back(layout.names[static_cast<std::size_t>(i)]);
  }
  return out;
}

Result<ToolSensitivity> ToolSensitivityModel::at(const Pose& pose) const {
  auto readings = base_->inverse(pose);
  if (!readings) return readings.error();
  const int n = parameters();
  ToolSensitivity g = ToolSensitivity::Zero(3, n);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    auto plus = plus_[k]->forward(*readings, pose, fk_);
    if (!plus) return tool_derivative_error(names_[k], plus.error());
    auto minus = minus_[k]->forward(*readings, pose, fk_);
    if (!minus) return tool_derivative_error(names_[k], minus.error());
    g.col(i) = (plus->pose.position_mm - minus->pose.position_mm) / (2.0 * steps_[k]);
  }
  return g;
}

Result<std::vector<ToolSensitivity>> tool_point_sensitivities(const Mechanism& model,
                                                              const ParameterLayout& layout,
                                                              const Eigen::VectorXd& parameters,
                                                              const std::vector<Pose>& poses,
                                                              const ResidualOptions& options) {
  auto sensitivity = ToolSensitivityModel::make(model, layout, parameters, options);
  if (!sensitivity) return sensitivity.error();
  const int count = static_cast<int>(poses.size());
  std::vector<ToolSensitivity> g(poses.size());
  std::vector<std::optional<Error>> errors(poses.size());
  tbb::parallel_for(0, count, [&](int p) {
    const auto k = static_cast<std::size_t>(p);
    auto g_at = sensitivity->at(poses[k]);
    if (g_at) {
      g[k] = std::move(*g_at);
    } else {
      errors[k] = g_at.error();
    }
  });
  for (int p = 0; p < count; ++p) {
    if (const auto& e = errors[static_cast<std::size_t>(p)])
      return make_error(e->code, fmt::format("pose {}: {}", p + 1, e->message));
  }
  return g;
}

}  // namespace pkm::calibration
