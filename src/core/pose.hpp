#pragma once
// A pose: the tool point in the base frame plus the platform orientation.
//   r_base = rotation · r_tool_frame + position_mm
// Platform-fixed points (joints) are given in the tool frame, whose origin is the tool point.
#include <Eigen/Core>
#include <array>

#include "core/rotation.hpp"

namespace pkm {

struct Pose {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();

  Eigen::Vector3d to_base(const Eigen::Vector3d& point_tool_frame_mm) const {
    return rotation * point_tool_frame_mm + position_mm;
  }
};

/// The six user-facing pose coordinates: x, y, z in mm and three angles in the machine's convention.
/// `PoseVector` holds the angles in radians; files and the CLI use degrees (see pose_io.hpp).
using PoseVector = Eigen::Matrix<double, 6, 1>;

Pose pose_from_vector(AngleConvention convention, const PoseVector& coordinates_mm_rad);
PoseVector vector_from_pose(AngleConvention convention, const Pose& pose);

/// Position and orientation distance between two poses: |Δp| in mm and rotation angle in rad.
struct PoseDistance {
  double position_mm;
  double rotation_rad;
};
PoseDistance pose_distance(const Pose& a, const Pose& b);

}  // namespace pkm
