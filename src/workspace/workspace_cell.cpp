#include "workspace/workspace_cell.hpp"

#include <array>
#include <cmath>

#include "machine/conditioning.hpp"
#include "machine/joint_limits.hpp"

namespace pkm::workspace {
namespace {

// The machine's own checks (check_actuator_range, check_joint_limits, check_conditioning_limit) build a
// message when they fail, which allocates; a map meets that at thousands of cells. These compare the same
// limits in the same order and keep which actuator or joint failed instead of a message.

// As check_actuator_range: actuator by actuator, actuator_min before actuator_max.
bool cell_within_actuator_range(const ActuatorLimits& limits, const double* actuators, int count,
                                WorkspaceCell& cell) {
  for (int j = 0; j < count; ++j) {
    const bool below = limits.min && actuators[j] < *limits.min;
    const bool above = limits.max && actuators[j] > *limits.max;
    if (below || above) {
      cell.status = CellStatus::actuator_range;
      cell.limit = below ? CellLimit::actuator_min : CellLimit::actuator_max;
      cell.limit_index = static_cast<std::int8_t>(j);
      return false;
    }
  }
  return true;
}

// As check_joint_limits: strut by strut, the base-side joint before the platform-side one. A NaN angle (a
// strut of zero length) fails, as the check's cosine comparison does.
bool cell_within_joint_limits(const Machine& machine, const Pose& pose, WorkspaceCell& cell) {
  const JointLimits& limits = machine.joint_limits;
  if (machine.joint_axes.count == 0 || !(limits.base_joint_max_rad || limits.platform_joint_max_rad))
    return true;
  const PassiveJointAngles angles = passive_joint_angles(machine, pose);
  for (int j = 0; j < angles.count; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const bool base = limits.base_joint_max_rad && !(angles.base_rad[k] <= *limits.base_joint_max_rad);
    const bool platform =
        limits.platform_joint_max_rad && !(angles.platform_rad[k] <= *limits.platform_joint_max_rad);
    if (base || platform) {
      cell.status = CellStatus::joint_angle;
      cell.limit = base ? CellLimit::base_joint : CellLimit::platform_joint;
      cell.limit_index = static_cast<std::int8_t>(j);
      return false;
    }
  }
  return true;
}

}  // namespace

const char* to_string(CellStatus status) {
  switch (status) {
    case CellStatus::ok:
      return "ok";
    case CellStatus::unreachable:
      return "unreachable";
    case CellStatus::actuator_range:
      return "actuator_range";
    case CellStatus::joint_angle:
      return "joint_angle";
    case CellStatus::singular:
      return "singular";
    case CellStatus::conditioning:
      return "conditioning";
  }
  return "unreachable";
}

void evaluate_cell_kinematics(const Machine& machine, const Pose& pose, WorkspaceCell& cell,
                              Pose& completed) {
  cell = WorkspaceCell{};
  const Mechanism& mechanism = *machine.mechanism;
  auto full = mechanism.complete_pose(pose);
  if (!full) return;  // unreachable: the constraints have no solution there
  completed = *full;
  std::array<double, kMaxActuators> actuators{};
  const int n = mechanism.actuator_count();
  if (!mechanism.actuator_values(completed, actuators.data())) return;

  // The geometry's measures first: they are drawn also where a limit stops the machine (Figs. 161–162).
  auto measures = jacobian_measures(mechanism, completed);
  const bool regular = measures.ok();
  if (regular) {
    cell.condition_number = measures->condition_number;
    // δρ and S need J⁻¹: jacobian_measures leaves them zero for a J that is not square.
    if (n == mechanism.controlled_axes().count()) {
      cell.determinant_sign =
          static_cast<std::int8_t>((measures->determinant > 0) - (measures->determinant < 0));
      cell.error_amplification = measures->error_amplification;
      cell.sensitivity_sums = measures->sensitivity_sums;
    }
  }

  // The limits in the planner's order (path_sampling.cpp): actuator range, joint swings, conditioning.
  cell.status = CellStatus::ok;
  if (!cell_within_actuator_range(machine.limits, actuators.data(), n, cell)) return;
  if (!cell_within_joint_limits(machine, completed, cell)) return;
  if (!regular) {
    cell.status = CellStatus::singular;
    return;
  }
  const auto& max_condition = machine.joint_limits.max_condition_number;
  if (max_condition && !(cell.condition_number <= *max_condition)) {
    cell.status = std::isfinite(cell.condition_number) ? CellStatus::conditioning : CellStatus::singular;
    cell.limit = CellLimit::condition_number;
  }
}

}  // namespace pkm::workspace
