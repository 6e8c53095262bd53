#pragma once
// How the tool point the machine reaches for given drive readings depends on its parameters:
// G = ∂ tool point(FK_θ(readings)) / ∂θ, 3 × parameters, mm per unit of each parameter, by central
// differences (the same step as the identification Jacobian, parameter_jacobian.hpp). A parameter covariance
// Σ then gives the tool point's covariance G·Σ·Gᵀ at that pose: the predicted accuracy of a calibrated
// machine.
#include <Eigen/Core>
#include <vector>

#include "calibration/calibration_parameters.hpp"
#include "calibration/residuals.hpp"

namespace pkm::calibration {

using ToolSensitivity = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// G at each of `poses` for the readings IK_θ(pose) of the model at `parameters` (a machine commanded with
/// that model). Fails where a pose is out of reach or a stepped model has no forward solution.
Result<std::vector<ToolSensitivity>> tool_point_sensitivities(const Mechanism& model,
                                                              const ParameterLayout& layout,
                                                              const Eigen::VectorXd& parameters,
                                                              const std::vector<Pose>& poses,
                                                              const ResidualOptions& options = {});

}  // namespace pkm::calibration
