#include "machine/joint_limits.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace pkm {
namespace {

// The base-frame neutral axis of base joint j: turned with its carriage where the mounts turn.
Eigen::Vector3d base_axis(const PassiveJointAxes& axes, const StrutJointPoints& points, int j) {
  const Eigen::Vector3d& a = axes.base[j];
  if (!points.mounts_turn) return a;
  const double c = std::cos(points.mount_yaw_rad[j]), s = std::sin(points.mount_yaw_rad[j]);
  return {c * a.x() - s * a.y(), s * a.x() + c * a.y(), a.z()};
}

// The angle between a unit strut direction and a unit axis from their chord, 2·asin(|u − a|/2): accurate near
// 0, where acos of the dot product loses half the digits, and cheaper than atan2 of the cross and dot
// products. NaN stays NaN.
double swing_rad(const Eigen::Vector3d& unit_strut, const Eigen::Vector3d& unit_axis) {
  const double half_chord = 0.5 * (unit_strut - unit_axis).norm();
  return 2.0 * std::asin(half_chord > 1.0 ? 1.0 : half_chord);  // rounding can pass 1
}

// dot ≥ min_cos·|strut| without the square root of |strut|² (this is the check's inner loop): the squares
// compare on the side of 0 the two sides are on. A zero-length strut (no direction) or a NaN fails.
bool within(double dot, double length_sq, double min_cos) {
  const double bound_sq = min_cos * min_cos * length_sq;
  const bool inside =
      min_cos >= 0.0 ? (dot >= 0.0 && dot * dot >= bound_sq) : (dot >= 0.0 || dot * dot <= bound_sq);
  return length_sq > 0.0 && inside;
}

Error joint_error(const Machine& machine, const char* side, int j, double angle_rad, double limit_rad,
                  int line) {
  return make_error(
      ErrorCode::limit_exceeded,
      fmt::format("{} joint {} swings {:.1f} deg, beyond limits.{}_joint_max_deg = {:g} ({}:{})", side, j + 1,
                  deg_from_rad(angle_rad), side, deg_from_rad(limit_rad), machine.source, line));
}

// σ_max/σ_min of J, as jacobian_measures. Through the eigenvalues of JᵀJ (3× faster than an SVD of J, which
// matters at every planning sample); they lose the smallest singular value's digits once the condition number
// nears 1/√ε, so from 1e6 on the SVD of J decides.
// GCC 12 reports Eigen's eigenvalue-only solver as reading its (unused) eigenvector storage uninitialised
// once this is inlined; a known false positive, silenced here only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
double condition_number(const JacobianMatrix& j) {
  using Gram = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  const Gram gram = j.transpose() * j;
  const Eigen::SelfAdjointEigenSolver<Gram> eigen(gram, Eigen::EigenvaluesOnly);
  const auto& values = eigen.eigenvalues();  // ascending
  const double fast = values[0] > 0.0 ? std::sqrt(values[values.size() - 1] / values[0])
                                      : std::numeric_limits<double>::infinity();
  if (fast < 1e6) return fast;
  const Eigen::JacobiSVD<JacobianMatrix> svd(j);
  const auto& sv = svd.singularValues();
  const double smallest = sv[sv.size() - 1];
  return smallest > 0.0 ? sv[0] / smallest : std::numeric_limits<double>::infinity();
}
#pragma GCC diagnostic pop

}  // namespace

PassiveJointAngles passive_joint_angles(const Machine& machine, const Pose& pose) {
  PassiveJointAngles out;
  const PassiveJointAxes& axes = machine.joint_axes;
  if (axes.count == 0) return out;
  out.count = axes.count;
  StrutJointPoints points;
  if (machine.mechanism->strut_joints(pose, points) < 0) {
    out.base_rad.fill(std::numeric_limits<double>::quiet_NaN());
    out.platform_rad.fill(std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  for (int j = 0; j < axes.count; ++j) {
    const Eigen::Vector3d strut = points.platform_mm[j] - points.base_mm[j];
    // One division, not three; NaN for a zero-length strut, as its angles.
    const Eigen::Vector3d unit = strut * (1.0 / strut.norm());
    out.base_rad[j] = swing_rad(unit, base_axis(axes, points, j));
    out.platform_rad[j] = swing_rad(unit, points.platform_rotation * axes.platform[j]);
  }
  return out;
}

Status check_joint_limits(const Machine& machine, const Pose& pose) {
  const JointLimits& limits = machine.joint_limits;
  const PassiveJointAxes& axes = machine.joint_axes;
  const bool check_base = limits.base_joint_max_rad.has_value();
  const bool check_platform = limits.platform_joint_max_rad.has_value();
  if (axes.count == 0 || !(check_base || check_platform)) return ok_status();
  StrutJointPoints points;
  if (machine.mechanism->strut_joints(pose, points) < 0) {
    return make_error(ErrorCode::unreachable, "the pose is out of reach, so its joint angles are undefined");
  }
  for (int j = 0; j < axes.count; ++j) {
    const Eigen::Vector3d strut = points.platform_mm[j] - points.base_mm[j];
    const double length_sq = strut.squaredNorm();
    // cos(angle) ≥ cos(limit) ⇔ angle ≤ limit on [0, π].
    if (check_base) {
      const Eigen::Vector3d axis = base_axis(axes, points, j);
      if (!within(strut.dot(axis), length_sq, limits.base_joint_min_cos)) {
        return joint_error(machine, "base", j, swing_rad(strut * (1.0 / std::sqrt(length_sq)), axis),
                           *limits.base_joint_max_rad, limits.base_joint_max_line);
      }
    }
    if (check_platform) {
      // strut·(R·a) = (Rᵀ·strut)·a: the axis turned into the base frame, one product either way.
      const Eigen::Vector3d axis = points.platform_rotation * axes.platform[j];
      if (!within(strut.dot(axis), length_sq, limits.platform_joint_min_cos)) {
        return joint_error(machine, "platform", j, swing_rad(strut * (1.0 / std::sqrt(length_sq)), axis),
                           *limits.platform_joint_max_rad, limits.platform_joint_max_line);
      }
    }
  }
  return ok_status();
}

Result<double> jacobian_condition_number(const Mechanism& mechanism, const Pose& pose) {
  auto jacobian = mechanism.jacobian(pose);
  if (!jacobian) return jacobian.error();
  return condition_number(*jacobian);
}

Status check_conditioning_limit(const Machine& machine, const Pose& pose) {
  const JointLimits& limits = machine.joint_limits;
  if (!limits.max_condition_number) return ok_status();
  auto jacobian = machine.mechanism->jacobian(pose);
  if (!jacobian) return jacobian.error();
  const double condition = condition_number(*jacobian);
  if (condition <= *limits.max_condition_number) return ok_status();
  if (!std::isfinite(condition)) {
    return make_error(
        ErrorCode::singular,
        fmt::format("the Jacobian is singular (condition number infinite), beyond "
                    "limits.max_condition_number = {:g} ({}:{})",
                    *limits.max_condition_number, machine.source, limits.max_condition_number_line));
  }
  return make_error(
      ErrorCode::limit_exceeded,
      fmt::format("the Jacobian's condition number {:.1f} is beyond limits.max_condition_number = "
                  "{:g} ({}:{})",
                  condition, *limits.max_condition_number, machine.source, limits.max_condition_number_line));
}

}  // namespace pkm
