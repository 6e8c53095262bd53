#pragma once
// The numbers calibration identifies, as one vector (Smirnov 2019, §5.2.4): a mechanism's geometry groups
// (Mechanism::geometry_parameters, e.g. the hexapod's base joints A1..A6 and platform joints B1..B6, plus the
// drive offsets dL1..dL6 of machine/actuator_offsets.hpp: 18 + 18 + 6 = 42, the dissertation's 36 joint
// coordinates and 6 initial strut lengths) flattened in group order, row-major, with a name per scalar.
//
// Conditioning: every parameter has a scale, the millimetres one unit of it moves a point of the machine, so
// that Jacobian columns over the scaled parameters u = θ / scale compare (mm: 1; angles and other units: the
// platform size, Mechanism::platform_size_mm). The SVD diagnostics of identify.hpp work in these units.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "machine/mechanism.hpp"

namespace pkm::calibration {

struct ParameterLayout {
  std::vector<GeometryGroup> groups;    ///< shapes and names; values are those the layout was made from
  std::vector<std::string> names;       ///< per scalar: "A3.x", "B5.z", "dL3"
  std::vector<std::string> units;       ///< per scalar: the group's unit
  std::vector<std::string> group_keys;  ///< per scalar: the group's key ("base_joints", "actuator_offsets")
  std::vector<int> rows;   ///< per scalar: the row in its group (strut j − 1 for per-strut groups)
  Eigen::VectorXd scale;   ///< per scalar: mm moved per unit (see above), > 0
  int actuator_count = 0;  ///< of the mechanism: groups with this many rows are per strut
  int size() const { return static_cast<int>(names.size()); }
};

/// The layout of a mechanism's geometry groups; fails for a mechanism without any.
Result<ParameterLayout> parameter_layout(const Mechanism& mechanism);

/// The groups' values as one vector, in layout order.
Eigen::VectorXd parameter_vector(const std::vector<GeometryGroup>& groups);

/// The layout's groups with the values of `parameters` (size() numbers).
std::vector<GeometryGroup> groups_from_vector(const ParameterLayout& layout,
                                              const Eigen::VectorXd& parameters);

/// `model` rebuilt with the values of `parameters` (Mechanism::with_geometry): same convention, home, mode.
Result<std::unique_ptr<Mechanism>> mechanism_with_parameters(const Mechanism& model,
                                                             const ParameterLayout& layout,
                                                             const Eigen::VectorXd& parameters);

/// Index of the parameter named `name`, −1 when there is none.
int parameter_index(const ParameterLayout& layout, std::string_view name);

}  // namespace pkm::calibration
