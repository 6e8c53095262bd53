#include "machine/tricept.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "kinematics/damped_newton.hpp"

namespace pkm {

Tricept::Tricept(const TriceptGeometry& geometry, AngleConvention convention)
    : geometry_(geometry), convention_(convention) {
  for (int j = 0; j < 3; ++j) {
    platform_tool_mm_[j] = geometry_.platform_joints_mm[j] - Eigen::Vector3d(0, 0, geometry_.tool_offset_mm);
  }
}

Result<Tricept> Tricept::create(const TriceptGeometry& geometry, AngleConvention convention,
                                const Eigen::Vector3d& home_position_mm) {
  const auto& b = geometry.platform_joints_mm;
  const Eigen::Vector3d u = b[1] - b[0], v = b[2] - b[0];
  if (!(u.cross(v).squaredNorm() > 1e-12 * u.squaredNorm() * v.squaredNorm()) || u.isZero() || v.isZero()) {
    return make_error(ErrorCode::bad_input, "the three flange joints are collinear");
  }
  Tricept tricept(geometry, convention);
  Pose home;
  home.position_mm = home_position_mm;
  auto complete = tricept.complete_pose(home);
  if (!complete) return complete.error();
  tricept.home_ = *complete;
  Eigen::Vector3d lengths;
  Eigen::Matrix3d j;
  if (!tricept.evaluate(home_position_mm, lengths, &j)) {
    return make_error(ErrorCode::unreachable, "a strut has zero length at the home pose");
  }
  if (!(Eigen::PartialPivLU<Eigen::Matrix3d>(j).rcond() > 1e-9)) {
    return make_error(ErrorCode::singular, "the tricept is singular at its home pose (det dL/dP = 0)");
  }
  tricept.home_sign_ = j.determinant() >= 0 ? 1 : -1;
  return tricept;
}

bool Tricept::axis_of(const Eigen::Vector3d& p, TriceptAxis& axis) const noexcept {
  // The tool point lies on the axis beyond O: P − O = (ρ + tool_offset)·e, e = B·e_z = (C − O)/ρ.
  const Eigen::Vector3d r = p - geometry_.center_joint_mm;
  const double d = r.norm();
  if (!(d > 0.0) || !(r.z() > 0.0)) return false;  // |α| < 90°: the axis points to the +z side of O
  axis.rho_mm = d - geometry_.tool_offset_mm;
  if (!(axis.rho_mm > 0.0)) return false;
  // (34), (35) with atan2 for the quadrants (Smirnov 2019, §2.2.7); r has the direction of C − O.
  axis.alpha_rad = std::atan2(-r.y(), r.z());
  axis.beta_rad = std::atan2(r.x(), std::hypot(r.y(), r.z()));
  axis.center_mm = geometry_.center_joint_mm + (axis.rho_mm / d) * r;
  return true;
}

Eigen::Matrix3d Tricept::angular_rate_per_tool_velocity(const Eigen::Vector3d& p,
                                                        const TriceptAxis& axis) const noexcept {
  // ω = α̇·e_x + β̇·Rx(α)e_y with ∇α, ∇β from (34), (35).
  const Eigen::Vector3d r = p - geometry_.center_joint_mm;
  const double yz_sq = r.y() * r.y() + r.z() * r.z();
  const double s = std::sqrt(yz_sq);
  const double d_sq = yz_sq + r.x() * r.x();
  const Eigen::Vector3d grad_alpha(0.0, -r.z() / yz_sq, r.y() / yz_sq);
  const Eigen::Vector3d grad_beta(s / d_sq, -r.x() * r.y() / (s * d_sq), -r.x() * r.z() / (s * d_sq));
  return Eigen::Vector3d::UnitX() * grad_alpha.transpose() +
         rot_x(axis.alpha_rad).col(1) * grad_beta.transpose();
}

bool Tricept::controlled_twists(const Pose& pose, TwistBasis& out) const noexcept {
  TriceptAxis axis;
  if (!axis_of(pose.position_mm, axis)) return false;
  out.resize(6, 3);
  out.topRows<3>().setIdentity();
  out.bottomRows<3>() = angular_rate_per_tool_velocity(pose.position_mm, axis);
  return true;
}

bool Tricept::evaluate(const Eigen::Vector3d& p, Eigen::Vector3d& lengths_mm,
                       Eigen::Matrix3d* jacobian) const noexcept {
  TriceptAxis axis;
  if (!axis_of(p, axis)) return false;
  const Eigen::Matrix3d rotation = rot_x(axis.alpha_rad) * rot_y(axis.beta_rad);  // (36): B = Rx(α)·Ry(β)
  const Eigen::Matrix3d omega =
      jacobian != nullptr ? angular_rate_per_tool_velocity(p, axis) : Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d arm = rotation * platform_tool_mm_[j];
    const Eigen::Vector3d strut = p + arm - geometry_.base_joints_mm[j];
    lengths_mm[j] = strut.norm();
    if (!(lengths_mm[j] > 0.0)) return false;
    if (jacobian != nullptr) {
      const Eigen::Vector3d unit = strut / lengths_mm[j];
      // dL = u·(dP + ω × arm) = (u + Ωᵀ(arm × u))·dP
      jacobian->row(j) = unit.transpose() + arm.cross(unit).transpose() * omega;
    }
  }
  return true;
}

Result<Pose> Tricept::complete_pose(const Pose& pose) const {
  TriceptAxis axis;
  if (!axis_of(pose.position_mm, axis)) {
    const Eigen::Vector3d r = pose.position_mm - geometry_.center_joint_mm;
    std::string why;
    if (!(r.norm() > 0.0)) {
      why = "the tool point is on the central joint O";
    } else if (!(r.z() > 0.0)) {
      why = "the manipulator axis would point to or below the horizontal through the central joint O";
    } else {
      why = fmt::format("the central leg would need |OC| = {:.3f} mm <= 0 (tool offset {:.3f} mm)",
                        r.norm() - geometry_.tool_offset_mm, geometry_.tool_offset_mm);
    }
    return make_error(ErrorCode::unreachable,
                      fmt::format("tool point ({:.3f}, {:.3f}, {:.3f}) mm is out of reach: {}",
                                  pose.position_mm.x(), pose.position_mm.y(), pose.position_mm.z(), why));
  }
  Pose out;
  out.position_mm = pose.position_mm;
  out.rotation = rot_x(axis.alpha_rad) * rot_y(axis.beta_rad);
  return out;
}

Result<ActuatorVector> Tricept::inverse(const Pose& pose) const {
  auto complete = complete_pose(pose);
  if (!complete) return complete.error();
  Eigen::Vector3d lengths;
  if (!evaluate(pose.position_mm, lengths, nullptr)) {
    return make_error(ErrorCode::unreachable,
                      "a strut would have zero length: flange joint on its base joint");
  }
  ActuatorVector out(3);
  out = lengths;
  return out;
}

bool Tricept::actuator_values(const Pose& pose, double* out) const noexcept {
  // As inverse(): evaluate() fails exactly where complete_pose() does (no manipulator axis) or a strut
  // would have zero length.
  Eigen::Vector3d lengths;
  if (!evaluate(pose.position_mm, lengths, nullptr)) return false;
  for (int j = 0; j < 3; ++j) out[j] = lengths[j];
  return true;
}

int Tricept::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  auto complete = complete_pose(pose);
  if (!complete) return -1;
  for (int j = 0; j < 3; ++j) {
    out.base_mm[j] = geometry_.base_joints_mm[j];
    out.platform_mm[j] = complete->to_base(platform_tool_mm_[j]);
  }
  out.platform_rotation = complete->rotation;
  out.mounts_turn = false;
  return 3;
}

bool Tricept::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  auto complete = complete_pose(pose);
  if (!complete) return false;
  StrutJointPoints joints;
  if (strut_joints(*complete, joints) != 3) return false;
  return strut_length_twist_jacobian(joints, 3, complete->position_mm, out);
}

Result<JacobianMatrix> Tricept::jacobian(const Pose& pose) const {
  auto complete = complete_pose(pose);
  if (!complete) return complete.error();
  Eigen::Vector3d lengths;
  Eigen::Matrix3d j;
  if (!evaluate(pose.position_mm, lengths, &j)) {
    return make_error(ErrorCode::singular, "a strut has zero length: its direction is undefined");
  }
  JacobianMatrix out(3, 3);
  out = j;
  return out;
}

Result<FkSolution> Tricept::forward(const ActuatorVector& q, const Pose& guess,
                                    const FkOptions& options) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("a tricept needs 3 strut lengths, got {}", q.size()));
  }
  const Eigen::Vector3d target = q.head<3>();
  for (int j = 0; j < 3; ++j) {
    if (!(target[j] > 0.0)) {
      return make_error(ErrorCode::bad_input, fmt::format("strut {} length must be positive", j + 1));
    }
  }
  // Damped Newton on the tool point (3 unknowns, eq. 38), with a backtracking line search on |L(P) − q|.
  Eigen::Vector3d guess_lengths;
  Eigen::Matrix3d guess_jacobian;
  if (!evaluate(guess.position_mm, guess_lengths, &guess_jacobian)) {
    return make_error(ErrorCode::unreachable,
                      "forward kinematics: the start guess is outside the reachable space");
  }
  const int guess_sign = guess_jacobian.determinant() >= 0 ? 1 : -1;  // assembly mode of the guess
  auto residual = [&](const Eigen::Vector3d& point, Eigen::Vector3d& f, Eigen::Matrix3d& j) {
    Eigen::Vector3d lengths;
    if (!evaluate(point, lengths, &j)) return false;
    f = lengths - target;
    return true;
  };
  NewtonState<3> state;
  switch (damped_newton<3>(residual, guess.position_mm, Eigen::Vector3d::Ones(), options, state)) {
    case NewtonStatus::converged:
      break;
    case NewtonStatus::start_outside:
      return make_error(ErrorCode::unreachable,
                        "forward kinematics: the start guess is outside the reachable space");
    case NewtonStatus::singular_on_the_way:
      return make_error(ErrorCode::singular,
                        "forward kinematics: the Jacobian is singular on the way to a solution "
                        "(the strut lengths may lie at a singular configuration)");
    case NewtonStatus::singular_at_solution:
      return make_error(
          ErrorCode::singular,
          "forward kinematics: these strut lengths put the tricept in a singular configuration");
    case NewtonStatus::not_converged:
      return make_error(
          ErrorCode::not_converged,
          fmt::format("forward kinematics did not converge within {} iterations (residual {:.3g} mm); "
                      "the strut lengths may be out of reach, or give a guess closer to the solution",
                      options.max_iterations, state.residual_mm));
  }
  const Eigen::Vector3d p = state.x;
  const Eigen::Matrix3d& j = state.jacobian;
  FkSolution solution;
  solution.pose.position_mm = p;
  TriceptAxis axis;
  axis_of(p, axis);
  solution.pose.rotation = rot_x(axis.alpha_rad) * rot_y(axis.beta_rad);
  solution.iterations = state.iterations;
  solution.residual_mm = state.residual_mm;
  const int sign = j.determinant() >= 0 ? 1 : -1;
  solution.branch = sign == home_sign_ ? 0 : 1;
  if (options.require_same_branch && sign != guess_sign) {
    return another_assembly_mode_error(solution.pose);
  }
  return solution;
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Tricept::geometry_parameters() const {
  return {point_group("base_joints", "A", geometry_.base_joints_mm.data(), 3),
          point_group("platform_joints", "B", geometry_.platform_joints_mm.data(), 3),
          point_group("center_joint", "O", &geometry_.center_joint_mm, 1)};
}

Result<std::unique_ptr<Mechanism>> Tricept::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  TriceptGeometry geometry = geometry_;
  for (int j = 0; j < 3; ++j) {
    geometry.base_joints_mm[j] = group_point(groups[0], j);
    geometry.platform_joints_mm[j] = group_point(groups[1], j);
  }
  geometry.center_joint_mm = group_point(groups[2], 0);
  auto tricept = Tricept::create(geometry, convention_, home_.position_mm);
  if (!tricept) return tricept.error();
  return std::unique_ptr<Mechanism>(std::make_unique<Tricept>(std::move(tricept.value())));
}

}  // namespace pkm
