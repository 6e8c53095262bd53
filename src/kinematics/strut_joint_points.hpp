#pragma once
// Where the struts' passive joints are at a pose, for joint-angle limits (machine/joint_limits.hpp), drawing,
// statics and stiffness.
#include <Eigen/Core>
#include <array>

#include "kinematics/actuator_vector.hpp"

namespace pkm {

/// Strut j runs from its base-side joint base_mm[j] to its platform-side joint platform_mm[j] (base frame).
struct StrutJointPoints {
  std::array<Eigen::Vector3d, kMaxActuators> base_mm;
  std::array<Eigen::Vector3d, kMaxActuators> platform_mm;
  /// The platform's orientation at the (completed) pose: platform-side joints are mounted on the platform.
  Eigen::Matrix3d platform_rotation = Eigen::Matrix3d::Identity();
  /// Base joints on carriages that turn as they move (rotopod: round the circle) are mounted on the carriage:
  /// mount_yaw_rad[j] is the carriage's turn about the base z axis (its angle on the circle). Otherwise the
  /// mounts keep their orientation (fixed joints, carriages on straight guides) and mounts_turn is false.
  std::array<double, kMaxActuators> mount_yaw_rad{};
  bool mounts_turn = false;
};

}  // namespace pkm
