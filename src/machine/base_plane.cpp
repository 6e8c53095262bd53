#include "machine/base_plane.hpp"

#include <Eigen/SVD>

namespace pkm {

BasePlane::BasePlane(const std::array<Eigen::Vector3d, 6>& base_joints_mm,
                     const std::array<Eigen::Vector3d, 6>& platform_joints_tool_mm, const Pose& home) {
  for (const auto& a : base_joints_mm) centroid_mm_ += a / 6.0;
  Eigen::Matrix<double, 3, 6> spread;
  for (int j = 0; j < 6; ++j) spread.col(j) = base_joints_mm[j] - centroid_mm_;
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 6>> svd(spread, Eigen::ComputeFullU);
  normal_ = svd.matrixU().col(2);
  Eigen::Vector3d platform_centroid = Eigen::Vector3d::Zero();
  for (const auto& b : platform_joints_tool_mm) platform_centroid += home.to_base(b) / 6.0;
  if (normal_.dot(platform_centroid - centroid_mm_) < 0) normal_ = -normal_;
}

int BasePlane::side_code(const Pose& pose,
                         const std::array<Eigen::Vector3d, 6>& platform_joints_tool_mm) const {
  bool all_above = true;
  bool all_below = true;
  // n·(R b + p − c) = (Rᵀn)·b + n·(p − c): one 3×3 product for all six joints.
  const Eigen::Vector3d n_platform = pose.rotation.transpose() * normal_;
  const double offset = normal_.dot(pose.position_mm - centroid_mm_);
  for (const auto& b : platform_joints_tool_mm) {
    const double side = n_platform.dot(b) + offset;
    all_above = all_above && side > 0;
    all_below = all_below && side < 0;
  }
  return all_above ? 0 : (all_below ? 2 : 4);
}

}  // namespace pkm
