#pragma once
// How the tool point the machine reaches for given drive readings depends on its parameters:
// G = ∂ tool point(FK_θ(readings)) / ∂θ, 3 × parameters, mm per unit of each parameter, by central
// differences (the same step as the identification Jacobian, parameter_jacobian.hpp). A parameter covariance
// Σ then gives the tool point's covariance G·Σ·Gᵀ at that pose: the predicted accuracy of a calibrated
// machine.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "calibration/calibration_parameters.hpp"
#include "calibration/residuals.hpp"

namespace pkm::calibration {

using ToolSensitivity = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// G at any pose of one model: the model and its stepped copies (θ ± step along each parameter) are built
/// once, so that a pose costs one IK and 2 × parameters forward solutions. Immutable once made: at() may be
/// called from several threads at once (a workspace map's cells).
class ToolSensitivityModel {
 public:
  /// The model at `parameters` and its stepped copies. Fails where a stepped model cannot be built.
  static Result<ToolSensitivityModel> make(const Mechanism& model, const ParameterLayout& layout,
                                           const Eigen::VectorXd& parameters,
                                           const ResidualOptions& options = {});

  /// G at `pose` for the readings IK_θ(pose) (a machine commanded with that model), each stepped model's
  /// forward kinematics started at `pose`. Fails where the pose is out of reach or a stepped model has no
  /// forward solution (the message names the parameter).
  Result<ToolSensitivity> at(const Pose& pose) const;

  int parameters() const { return static_cast<int>(steps_.size()); }

 private:
  std::unique_ptr<Mechanism> base_;
  std::vector<std::unique_ptr<Mechanism>> plus_, minus_;  ///< per parameter: θ + step, θ − step
  std::vector<double> steps_;                             ///< per parameter, in its unit
  std::vector<std::string> names_;
  FkOptions fk_;
};

/// G at each of `poses` for the readings IK_θ(pose) of the model at `parameters` (a machine commanded with
/// that model). Fails where a pose is out of reach or a stepped model has no forward solution.
Result<std::vector<ToolSensitivity>> tool_point_sensitivities(const Mechanism& model,
                                                              const ParameterLayout& layout,
                                                              const Eigen::VectorXd& parameters,
                                                              const std::vector<Pose>& poses,
                                                              const ResidualOptions& options = {});

}  // namespace pkm::calibration
