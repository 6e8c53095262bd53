#pragma once
// One cell of a workspace map: whether the machine may stand at the pose, and if not which limit stops it
// (the checks the planner makes at every sample, planning/path_sampling.cpp, in its order), and the pose's
// Jacobian measures (machine/conditioning.hpp): the sign of det J, the condition number and the error
// amplification of Smirnov 2019, §5.2.2,
//   S_x = Σ_j |∂x/∂L_j|, S_y, S_z (eq. 144),   δρ = ρ/ΔL = sqrt(S_x² + S_y² + S_z²) (eq. 145),
// the factor by which equal actuator errors ΔL reach the tool point, whose largest value over the working
// space bounds the actuator error allowed (eq. 146: ΔL ≤ ρ_MAX/δρ_MAX).
//
// The Jacobian measures are filled in wherever the pose is geometrically reachable and J regular, also where
// a limit stops the machine: the dissertation's Figs. 161–162 draw δρ "with the workspace limits ignored",
// and a map shows the field with the limits over it. The optional layers (stiffness, natural frequency, error
// after calibration) are filled in only where the status is ok: they describe the machine where it can stand.
#include <cstdint>
#include <limits>

#include "machine/machine.hpp"

namespace pkm::workspace {

/// Why the machine can or cannot stand at a cell's pose; the first of the planner's checks that fails.
enum class CellStatus : std::uint8_t {
  ok,              ///< within every limit of the machine file
  unreachable,     ///< no actuator values reach the pose (a strut too short for its guide, a tripod's
                   ///< constraint)
  actuator_range,  ///< an actuator leaves actuator_min … actuator_max (a glide's carriage leaves its travel)
  joint_angle,     ///< a passive joint swings beyond limits.base/platform_joint_max_deg
  singular,        ///< J cannot be inverted
  conditioning,    ///< the condition number exceeds limits.max_condition_number
};
inline constexpr int kCellStatusCount = 6;

/// "ok", "unreachable", "actuator_range", "joint_angle", "singular", "conditioning": the words of the CSV.
const char* to_string(CellStatus status);

/// Which limit a stopped cell meets (with WorkspaceCell::limit_index, the actuator or strut).
enum class CellLimit : std::uint8_t {
  none,
  actuator_min,      ///< the actuator is below actuator_min
  actuator_max,      ///< above actuator_max
  base_joint,        ///< the strut's base-side joint swings too far
  platform_joint,    ///< the strut's platform-side joint swings too far
  condition_number,  ///< limits.max_condition_number
};

struct WorkspaceCell {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  CellStatus status = CellStatus::unreachable;
  CellLimit limit = CellLimit::none;
  std::int8_t limit_index = -1;        ///< the actuator or strut of `limit`, 0-based; −1 for none
  std::int8_t determinant_sign = 0;    ///< sign of det J; 0 where J is singular, not square or not computed
  double condition_number = kNone;     ///< σ_max/σ_min of J (mm and rad)
  double error_amplification = kNone;  ///< δρ (eq. 145), mm of tool point per mm of equal actuator error
  Eigen::Vector3d sensitivity_sums = Eigen::Vector3d::Constant(kNone);  ///< S_x, S_y, S_z (eq. 144)
  double lowest_stiffness_N_um = kNone;  ///< the weakest principal translational stiffness (optional layer)
  double lowest_frequency_Hz = kNone;    ///< the lowest natural frequency (optional layer)
  double calibrated_error_mm = kNone;    ///< the predicted position error after calibration (optional layer)
};

/// The status and the Jacobian measures of the cell at `pose`, and the pose completed by the mechanism
/// (`completed`: what the optional layers are computed at). Never allocates where the pose is reachable and J
/// regular, whatever the limits say: the map's threads call it for every cell.
void evaluate_cell_kinematics(const Machine& machine, const Pose& pose, WorkspaceCell& cell, Pose& completed);

}  // namespace pkm::workspace
