#pragma once
// Singularity and accuracy measures of a pose: det J, condition number, and the error amplification δρ
// of Smirnov 2019, §5.2.2 (eq. 144–146): with equal actuator errors ΔL,
//   S_x = Σ_j |∂x/∂L_j|,  S_y, S_z likewise,   δρ = ρ/ΔL = sqrt(S_x² + S_y² + S_z²),
// where ∂x/∂L_j are entries of the inverse Jacobian (forward-kinematics sensitivities).
#include "machine/machine.hpp"

namespace pkm {

struct JacobianMeasures {
  double determinant = 0.0;       ///< of J in the controlled coordinates (angles in rad)
  double condition_number = 0.0;  ///< σ_max/σ_min of J (angles in rad)
  double min_singular_value = 0.0;
  double error_amplification = 0.0;  ///< δρ, mm of tool position per mm of equal actuator error
  Eigen::Vector3d sensitivity_sums = Eigen::Vector3d::Zero();  ///< (S_x, S_y, S_z); 0 for uncontrolled axes
};

/// Measures at a pose. Fails with ErrorCode::singular when J cannot be inverted.
Result<JacobianMeasures> jacobian_measures(const Mechanism& mechanism, const Pose& pose);

/// A box of poses around a centre: ± half-ranges on the controlled translations (mm) and angles (rad).
struct WorkspaceBox {
  Pose centre;
  double translation_half_range_mm = 50.0;
  double angle_half_range_rad = 0.0;
  int samples_per_axis = 5;
};

struct WorkspaceSummary {
  int poses = 0;
  int unreachable = 0;   ///< poses with no IK solution
  int out_of_range = 0;  ///< poses whose actuators leave the machine's range
  int singular = 0;      ///< poses where J is singular
  ActuatorVector actuator_min, actuator_max;
  double error_amplification_min = 0.0, error_amplification_max = 0.0;
  double condition_max = 0.0;
  bool determinant_changes_sign = false;
};

/// Grid over the controlled coordinates of the box (samples_per_axis^m poses, m ≤ 6).
WorkspaceSummary sample_workspace(const Machine& machine, const WorkspaceBox& box);

}  // namespace pkm
