#pragma once
// The assembly-mode label of a platform on six legs: which side of the base-joint plane its joints are on,
// and the sign of det J (a sign change means the pose lies across a singularity). The dissertation removes
// the ambiguity of L-coordinates by "all platform joints above the plane of the base joints" (§2.2.2).
#include <Eigen/Core>
#include <array>

#include "core/pose.hpp"

namespace pkm {

class BasePlane {
 public:
  /// Least-squares plane through the base joints, its normal towards the platform joints at `home`.
  BasePlane(const std::array<Eigen::Vector3d, 6>& base_joints_mm,
            const std::array<Eigen::Vector3d, 6>& platform_joints_tool_mm, const Pose& home);

  /// 0: every platform joint on the home side; 2: every one on the other side; 4: some on each (or on it).
  int side_code(const Pose& pose, const std::array<Eigen::Vector3d, 6>& platform_joints_tool_mm) const;
  /// side_code + 0 for det J ≥ 0, + 1 for det J < 0.
  int assembly_mode(const Pose& pose, const std::array<Eigen::Vector3d, 6>& platform_joints_tool_mm,
                    double jacobian_determinant) const {
    return side_code(pose, platform_joints_tool_mm) + (jacobian_determinant >= 0 ? 0 : 1);
  }

 private:
  Eigen::Vector3d centroid_mm_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_ = Eigen::Vector3d::UnitZ();
};

}  // namespace pkm
