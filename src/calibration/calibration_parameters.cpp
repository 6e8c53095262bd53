#include "calibration/calibration_parameters.hpp"

#include <fmt/format.h>

namespace pkm::calibration {

namespace {

std::string scalar_name(const GeometryGroup& group, int row, int column) {
  const std::string& suffix = group.column_names[static_cast<std::size_t>(column)];
  if (suffix.empty()) return fmt::format("{}{}", group.row_symbol, row + 1);
  return fmt::format("{}{}.{}", group.row_symbol, row + 1, suffix);
}

}  // namespace

Result<ParameterLayout> parameter_layout(const Mechanism& mechanism) {
  ParameterLayout layout;
  layout.actuator_count = mechanism.actuator_count();
  layout.groups = mechanism.geometry_parameters();
  if (layout.groups.empty()) {
    return make_error(ErrorCode::unsupported, fmt::format("a {} has no geometric parameters to calibrate",
                                                          to_string(mechanism.type())));
  }
  // Angles (and any unit but mm) are scaled by the lever that turns them into a displacement of the platform.
  const double lever_mm = mechanism.platform_size_mm();
  std::vector<double> scales;
  for (const GeometryGroup& group : layout.groups) {
    if (group.columns() == 0 || static_cast<int>(group.values.size()) != group.rows * group.columns()) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("geometry group '{}' has {} values for {} × {}", group.key,
                                    group.values.size(), group.rows, group.columns()));
    }
    for (int r = 0; r < group.rows; ++r) {
      for (int c = 0; c < group.columns(); ++c) {
        layout.names.push_back(scalar_name(group, r, c));
        layout.units.push_back(group.unit);
        layout.group_keys.push_back(group.key);
        layout.rows.push_back(r);
        scales.push_back(group.unit == "mm" ? 1.0 : lever_mm);
      }
    }
  }
  layout.scale = Eigen::Map<const Eigen::VectorXd>(scales.data(), static_cast<Eigen::Index>(scales.size()));
  return layout;
}

Eigen::VectorXd parameter_vector(const std::vector<GeometryGroup>& groups) {
  std::size_t count = 0;
  for (const GeometryGroup& group : groups) count += group.values.size();
  Eigen::VectorXd out(static_cast<Eigen::Index>(count));
  Eigen::Index k = 0;
  for (const GeometryGroup& group : groups) {
    for (double v : group.values) out[k++] = v;
  }
  return out;
}

std::vector<GeometryGroup> groups_from_vector(const ParameterLayout& layout,
                                              const Eigen::VectorXd& parameters) {
  std::vector<GeometryGroup> groups = layout.groups;
  Eigen::Index k = 0;
  for (GeometryGroup& group : groups) {
    for (double& v : group.values) v = k < parameters.size() ? parameters[k++] : v;
  }
  return groups;
}

Result<std::unique_ptr<Mechanism>> mechanism_with_parameters(const Mechanism& model,
                                                             const ParameterLayout& layout,
                                                             const Eigen::VectorXd& parameters) {
  if (parameters.size() != layout.size()) {
    return make_error(ErrorCode::bad_input, fmt::format("{} parameter values given for {} parameters",
                                                        parameters.size(), layout.size()));
  }
  return model.with_geometry(groups_from_vector(layout, parameters));
}

int parameter_index(const ParameterLayout& layout, std::string_view name) {
  for (int i = 0; i < layout.size(); ++i) {
    if (layout.names[static_cast<std::size_t>(i)] == name) return i;
  }
  return -1;
}

}  // namespace pkm::calibration
