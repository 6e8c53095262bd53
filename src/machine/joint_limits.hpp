#pragma once
// Passive-joint swing limits and the conditioning limit of the machine file's `limits:` section, checked at a
// pose (docs/machine-file.md). The swing of a strut's passive joint is the angle between the strut's
// direction and the joint's neutral axis (Machine::joint_axes): a universal or spherical joint only tilts so
// far before its housing touches the strut, so the planner checks it at every sample of a path.
#include <array>

#include "machine/machine.hpp"

namespace pkm {

/// Angles of the passive joints at a pose: per strut, the base-side and the platform-side swing, rad.
struct PassiveJointAngles {
  int count = 0;
  std::array<double, 6> base_rad{};
  std::array<double, 6> platform_rad{};
};

/// Computes them (count = 0 when the mechanism has no passive swing joints; NaN angles when the pose is out
/// of reach). Never allocates (hot path).
PassiveJointAngles passive_joint_angles(const Machine& machine, const Pose& pose);

/// ok, or ErrorCode::limit_exceeded naming the joint, its angle in degrees, the limit and the machine file
/// line, e.g. "platform joint 3 swings 41.2 deg, beyond limits.platform_joint_max_deg = 40
/// (hexapod.yaml:17)"; ErrorCode::unreachable when the pose is out of reach. ok when no joint limit is given.
/// Never allocates on success: it compares cosines, without square roots or trigonometry.
Status check_joint_limits(const Machine& machine, const Pose& pose);

/// The condition number σ_max/σ_min of the actuator Jacobian at a pose (mm and rad; infinite when singular).
Result<double> jacobian_condition_number(const Mechanism& mechanism, const Pose& pose);

/// ok, or limit_exceeded / singular when the Jacobian's condition number (σ_max/σ_min, mm and rad, as
/// jacobian_measures) exceeds limits.max_condition_number, naming the value, the limit and the file line. ok
/// when no limit is given. Never allocates on success.
Status check_conditioning_limit(const Machine& machine, const Pose& pose);

}  // namespace pkm
