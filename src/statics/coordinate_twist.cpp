#include "statics/coordinate_twist.hpp"

#include <fmt/format.h>

namespace pkm::statics {
namespace {

TwistBasis statics_analytic_basis(const Mechanism& mechanism, const Pose& pose) {
  const AngleConvention convention = mechanism.convention();
  const Eigen::Matrix3d e =
      angular_velocity_matrix(convention, angles_from_rotation(convention, pose.rotation));
  const AxisMask mask = mechanism.controlled_axes();
  TwistBasis basis = TwistBasis::Zero(6, mask.count());
  int column = 0;
  for (int axis = 0; axis < 6; ++axis) {
    if (!mask.controlled[axis]) continue;
    if (axis < 3) {
      basis(axis, column) = 1.0;
    } else {
      basis.block<3, 1>(3, column) = e.col(axis - 3);
    }
    ++column;
  }
  return basis;
}

}  // namespace

Result<TwistBasis> controlled_twist_basis(const Mechanism& mechanism, const Pose& completed_pose) {
  const AxisMask mask = mechanism.controlled_axes();
  if (mask.count() == 6 || mechanism.is_planar()) {
    return statics_analytic_basis(mechanism, completed_pose);
  }
  const AngleConvention convention = mechanism.convention();
  const PoseVector centre = vector_from_pose(convention, completed_pose);
  const auto names = pose_coordinate_names(mechanism);
  TwistBasis basis(6, mask.count());
  int column = 0;
  for (int axis = 0; axis < 6; ++axis) {
    if (!mask.controlled[axis]) continue;
    const double h = axis < 3 ? kTwistStepMm : kTwistStepRad;
    Pose side[2];
    for (int s = 0; s < 2; ++s) {
      PoseVector q = centre;
      q[axis] += s == 0 ? h : -h;
      auto pose = mechanism.complete_pose(pose_from_vector(convention, q));
      if (!pose) {
        return make_error(pose.error().code,
                          fmt::format("statics: the pose cannot be completed a step of {} {} away in {}: {}",
                                      h, axis < 3 ? "mm" : "rad", names[axis], pose.error().message));
      }
      side[s] = *pose;
    }
    // R₊R₋ᵀ = exp([ω]× 2h) + O(h³): the rotation vector of the central step is second-order accurate.
    basis.block<3, 1>(0, column) = (side[0].position_mm - side[1].position_mm) / (2.0 * h);
    basis.block<3, 1>(3, column) =
        rotation_vector_from_rotation(side[0].rotation * side[1].rotation.transpose()) / (2.0 * h);
    ++column;
  }
  return basis;
}

}  // namespace pkm::statics
