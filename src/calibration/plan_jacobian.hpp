#pragma once
// The identification Jacobian a plan would give, before anything is measured: noise-free measurements of the
// plan on the nominal machine (synthetic_measurements.hpp), their residual model and its Jacobian at the
// drawing. The information matrix JᵀJ of plan design and the predicted covariance follow from it.
#include <Eigen/Core>
#include <vector>

#include "calibration/calibration_parameters.hpp"
#include "calibration/residuals.hpp"
#include "calibration/synthetic_measurements.hpp"

namespace pkm::calibration {

struct PlanJacobian {
  ParameterLayout layout;
  Eigen::MatrixXd jacobian;    ///< weighted, column-scaled (parameter_jacobian.hpp)
  std::vector<int> first_row;  ///< per planned pose: its first row
  std::vector<int> rows;       ///< per planned pose: its row count
};

/// The Jacobian of measuring `poses` with `setup` on `nominal`. Fails for a mechanism without parameters or
/// a pose the nominal cannot reach.
Result<PlanJacobian> plan_jacobian(const Mechanism& nominal, const std::vector<Pose>& poses,
                                   const MeasurementSetup& setup, const ResidualOptions& options = {});

}  // namespace pkm::calibration
