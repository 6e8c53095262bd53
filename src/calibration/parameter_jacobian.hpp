#pragma once
// ∂(weighted residuals)/∂(scaled parameters) by central differences (the forward kinematics inside the
// residuals is implicit, so there is no closed form through the Mechanism interface): column i is
// (r(θ + h·s_i·e_i) − r(θ − h·s_i·e_i)) / 2h with h = ResidualOptions::derivative_step_mm and s_i the
// parameter's scale, i.e. the derivative over u_i = θ_i / s_i. The columns are independent and run in
// parallel (oneTBB).
#include <Eigen/Core>
#include <vector>

#include "calibration/calibration_parameters.hpp"
#include "calibration/residuals.hpp"

namespace pkm::calibration {

/// The Jacobian at `parameters` (physical values); `poses` are the FK starts at `parameters` (evaluate's).
/// Fails where a stepped model has no solution for a pose (the message names the parameter).
Result<Eigen::MatrixXd> residual_jacobian(const ResidualModel& residuals, const Mechanism& model,
                                          const ParameterLayout& layout, const Eigen::VectorXd& parameters,
                                          const std::vector<Pose>& poses);

}  // namespace pkm::calibration
