#include "machine/hexapod_refined.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "core/units.hpp"
#include "kinematics/coordinate_jacobian.hpp"
#include "kinematics/platform_newton.hpp"
#include "machine/solution_set.hpp"

namespace pkm {
namespace {

constexpr int kLegIterations = 30;
// Take the last Newton step once the strut end misses the platform joint by less than this; the result is
// then at the rounding level of a 1 m lever (≈1e-13 mm), far below any FK tolerance.
constexpr double kLegStopMm = 1e-11;
// Accept the per-leg solution only if its miss is below this after the iterations.
constexpr double kLegAcceptMm = 1e-9;
// |det| of the normalised leg map below this counts as gimbal lock.
constexpr double kLegMinNormalisedDet = 1e-10;

Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& unit_axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, unit_axis).toRotationMatrix();
}

// Angle about `axis` that turns the component of `from` normal to it onto that of `to` (Paden–Kahan
// subproblem 1).
double angle_about(const Eigen::Vector3d& axis, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d f = from - axis * axis.dot(from);
  const Eigen::Vector3d t = to - axis * axis.dot(to);
  return std::atan2(axis.dot(f.cross(t)), f.dot(t));
}

// Ideal-joint angles: Rot(a1, g1)·Rot(a2, g2)·u = d for unit a1, a2, u, d (Paden–Kahan subproblem 2). The
// middle vector z = Rot(a2, g2)·u = Rot(a1, −g1)·d satisfies a1·z = a1·d, a2·z = a2·u, |z| = 1. Of its two
// solutions the one with the smaller joint angles is the physical joint (the other has the yoke turned over).
void ideal_cardan_angles(const CardanJoint& joint, const Eigen::Vector3d& d, double& g1, double& g2) {
  const Eigen::Vector3d& a1 = joint.axis1;
  const Eigen::Vector3d& a2 = joint.axis2;
  const double c = a1.dot(a2);
  const double den = c * c - 1.0;  // axes validated far from parallel
  const double p = a1.dot(d);
  const double q = a2.dot(joint.strut_axis);
  const double alpha = (c * q - p) / den;
  const double beta = (c * p - q) / den;
  const Eigen::Vector3d n = a1.cross(a2);
  const double gamma = std::sqrt(
      std::fmax(0.0, (1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * c) / n.squaredNorm()));
  double best = -1.0;
  for (double sign : {1.0, -1.0}) {
    const Eigen::Vector3d z = alpha * a1 + beta * a2 + sign * gamma * n;
    const double t2 = angle_about(a2, joint.strut_axis, z);
    const double t1 = angle_about(a1, z, d);
    const double size = t1 * t1 + t2 * t2;
    if (best < 0.0 || size < best) {
      best = size;
      g1 = t1;
      g2 = t2;
    }
  }
}

// Eq. 28 for one leg with the columns ∂B/∂g1, ∂B/∂g2, ∂B/∂L.
Eigen::Vector3d strut_end_with_derivatives(const CardanJoint& joint, const Eigen::Vector3d& base_joint_mm,
                                           const CardanLegState& s, Eigen::Matrix3d* derivative) {
  const Eigen::Matrix3d rot1 = axis_rotation(joint.axis1, s.angle1_rad);
  const Eigen::Matrix3d rot2 = axis_rotation(joint.axis2, s.angle2_rad);
  const Eigen::Vector3d w2 = rot2 * (joint.strut_offset_mm + s.length_mm * joint.strut_axis);
  const Eigen::Vector3d w1 = rot1 * (joint.offset2_mm + w2);
  if (derivative) {
    derivative->col(0) = joint.axis1.cross(w1);
    derivative->col(1) = rot1 * joint.axis2.cross(w2);
    derivative->col(2) = rot1 * (rot2 * joint.strut_axis);
  }
  return base_joint_mm + joint.offset1_mm + w1;
}

}  // namespace

Eigen::Vector3d cardan_strut_end(const CardanJoint& joint, const Eigen::Vector3d& base_joint_mm,
                                 const CardanLegState& state) {
  return strut_end_with_derivatives(joint, base_joint_mm, state, nullptr);
}

CardanLegStatus solve_cardan_leg(const CardanJoint& joint, const Eigen::Vector3d& base_joint_mm,
                                 const Eigen::Vector3d& platform_joint_mm, CardanLegState& state,
                                 Eigen::Vector3d* dL_dB) {
  // Start: the ideal joint at A + R1 pointing at B (exact when all offsets are zero).
  const Eigen::Vector3d reach = platform_joint_mm - (base_joint_mm + joint.offset1_mm);
  state.length_mm = reach.norm();
  if (!(state.length_mm > 0.0)) return CardanLegStatus::folded;
  ideal_cardan_angles(joint, reach / state.length_mm, state.angle1_rad, state.angle2_rad);

  Eigen::Matrix3d derivative;
  bool converged = false;
  for (int iteration = 0; iteration < kLegIterations; ++iteration) {
    const Eigen::Vector3d miss =
        strut_end_with_derivatives(joint, base_joint_mm, state, &derivative) - platform_joint_mm;
    const double scale = derivative.col(0).norm() * derivative.col(1).norm() * derivative.col(2).norm();
    if (!(std::abs(derivative.determinant()) > kLegMinNormalisedDet * scale))
      return CardanLegStatus::singular;
    // Newton is quadratic: the step taken after the miss falls below kLegStopMm leaves only rounding.
    const Eigen::Vector3d step = derivative.inverse() * miss;
    state.angle1_rad -= step[0];
    state.angle2_rad -= step[1];
    state.length_mm -= step[2];
    if (miss.cwiseAbs().maxCoeff() <= kLegStopMm) {
      converged = true;
      break;
    }
  }
  if (!converged) {
    const Eigen::Vector3d miss = cardan_strut_end(joint, base_joint_mm, state) - platform_joint_mm;
    if (!(miss.cwiseAbs().maxCoeff() <= kLegAcceptMm)) return CardanLegStatus::not_converged;
  }
  // A cardan joint on a base cannot fold the strut past its mounting plane, and a strut has positive length.
  if (!(state.length_mm > 0.0) || !(std::abs(state.angle1_rad) < kPi / 2) ||
      !(std::abs(state.angle2_rad) < kPi / 2)) {
    return CardanLegStatus::folded;
  }
  // Implicit differentiation: d(g1, g2, L) = M⁻¹ dB, so ∂L/∂B is the last row of M⁻¹.
  if (dL_dB) *dL_dB = derivative.inverse().row(2).transpose();
  return CardanLegStatus::ok;
}

HexapodRefined::HexapodRefined(const HexapodGeometry& geometry, const std::array<CardanJoint, 6>& joints,
                               AngleConvention convention, const Pose& home)
    : geometry_(geometry),
      joints_(joints),
      convention_(convention),
      ideal_(geometry, convention, home),
      base_plane_(geometry.base_joints_mm, geometry.platform_joints_mm, home) {
  home_ = home;
  for (auto& joint : joints_) {
    joint.axis1.normalize();
    joint.axis2.normalize();
    joint.strut_axis.normalize();
  }
  home_mode_ = assembly_mode(home_);
}

Result<std::array<CardanLegState, 6>> HexapodRefined::leg_states(const Pose& pose) const {
  std::array<CardanLegState, 6> states;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d b = pose.to_base(geometry_.platform_joints_mm[j]);
    switch (solve_cardan_leg(joints_[j], geometry_.base_joints_mm[j], b, states[j])) {
      case CardanLegStatus::ok:
        break;
      case CardanLegStatus::folded:
        return make_error(
            ErrorCode::unreachable,
            fmt::format("strut {}: its cardan joint would have to fold past ±90° (angles {:.3f}°, "
                        "{:.3f}°, length {:.6f} mm)",
                        j + 1, deg_from_rad(states[j].angle1_rad), deg_from_rad(states[j].angle2_rad),
                        states[j].length_mm));
      case CardanLegStatus::singular:
        return make_error(
            ErrorCode::singular,
            fmt::format("strut {}: its cardan joint is in gimbal lock (strut along the first axis)", j + 1));
      case CardanLegStatus::not_converged:
        return make_error(
            ErrorCode::not_converged,
            fmt::format("strut {}: the cardan-joint equations (eq. 28) did not converge", j + 1));
    }
  }
  return states;
}

Result<ActuatorVector> HexapodRefined::inverse(const Pose& pose) const {
  auto states = leg_states(pose);
  if (!states) return states.error();
  ActuatorVector lengths(6);
  for (int j = 0; j < 6; ++j) lengths[j] = (*states)[j].length_mm;
  return lengths;
}

bool HexapodRefined::actuator_values(const Pose& pose, double* out) const noexcept {
  for (int j = 0; j < 6; ++j) {
    CardanLegState state;
    const Eigen::Vector3d b = pose.to_base(geometry_.platform_joints_mm[j]);
    if (solve_cardan_leg(joints_[j], geometry_.base_joints_mm[j], b, state) != CardanLegStatus::ok)
      return false;
    out[j] = state.length_mm;
  }
  return true;
}

Result<Eigen::Matrix<double, 6, 6>> HexapodRefined::twist_jacobian(const Pose& pose) const {
  Eigen::Matrix<double, 6, 6> jacobian;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d arm = pose.rotation * geometry_.platform_joints_mm[j];
    double length = 0.0;
    Eigen::Vector3d g;
    if (!leg_value(j, arm + pose.position_mm, length, g)) {
      auto states = leg_states(pose);  // for the message
      if (!states) return states.error();
      return make_error(ErrorCode::singular, fmt::format("strut {}: no derivative at this pose", j + 1));
    }
    jacobian.block<1, 3>(j, 0) = g.transpose();
    jacobian.block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
  return jacobian;
}

bool HexapodRefined::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  return joint_gradient_twist_jacobian(
      pose, 6, geometry_.platform_joints_mm,
      [this](int j, const Eigen::Vector3d& joint_mm, Eigen::Vector3d& g) {
        double length = 0.0;
        return leg_value(j, joint_mm, length, g);
      },
      out);
}

int HexapodRefined::assembly_mode(const Pose& pose) const {
  const auto twist = twist_jacobian(pose);
  if (!twist) return -1;
  return base_plane_.assembly_mode(pose, geometry_.platform_joints_mm, twist->determinant());
}

Result<FkSolution> HexapodRefined::forward(const ActuatorVector& actuators, const Pose& guess,
                                           const FkOptions& options) const {
  if (actuators.size() != 6) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("a refined hexapod needs 6 strut lengths, got {}", actuators.size()));
  }
  auto solution = solve_platform_fk(*this, true, actuators, guess, options);
  if (!solution) return solution;
  const int mode = assembly_mode(solution->pose);
  solution->branch = mode == home_mode_ ? 0 : mode + 1;
  const int guess_mode = options.require_same_branch ? assembly_mode(guess) : -1;
  if (guess_mode >= 0 && mode != guess_mode) {
    return another_assembly_mode_error(solution->pose);
  }
  return solution;
}

Result<AssemblyModes> HexapodRefined::assembly_modes(const ActuatorVector& actuators,
                                                     const FkOptions& options) const {
  if (actuators.size() != 6)
    return make_error(ErrorCode::bad_input, "a refined hexapod needs 6 strut lengths");
  // Joint errors move the solutions by about their own size, so the ideal modes are close guesses.
  auto ideal_modes = ideal_.assembly_modes(actuators, options);
  if (!ideal_modes) return ideal_modes.error();
  FkOptions polish = options;
  polish.require_same_branch = false;
  AssemblyModes modes;
  modes.report = ideal_modes->report;
  modes.report.method += ", polished on the refined model";
  for (const auto& ideal_solution : ideal_modes->solutions) {
    auto polished = solve_platform_fk(*this, true, actuators, ideal_solution.pose, polish);
    if (!polished) continue;
    if (contains_solution(modes.solutions, polished->pose)) continue;
    const int mode = assembly_mode(polished->pose);
    polished->branch = mode == home_mode_ ? 0 : mode + 1;
    modes.solutions.push_back(*polished);
  }
  modes.report.real = static_cast<int>(modes.solutions.size());
  if (modes.solutions.empty()) {
    return make_error(ErrorCode::unreachable,
                      "no assembly of the platform fits these strut lengths and joints");
  }
  return modes;
}

Result<std::vector<FkSolution>> HexapodRefined::forward_all(const ActuatorVector& actuators,
                                                            const FkOptions& options) const {
  auto modes = assembly_modes(actuators, options);
  if (!modes) return modes.error();
  return std::move(modes->solutions);
}

int HexapodRefined::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  return ideal_.strut_joints(pose, out);
}

Result<JacobianMatrix> HexapodRefined::jacobian(const Pose& pose) const {
  auto twist = twist_jacobian(pose);
  if (!twist) return twist.error();
  const JacobianMatrix t = *twist;
  return coordinate_jacobian(t, convention_, angles_from_rotation(convention_, pose.rotation),
                             AxisMask::all());
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> HexapodRefined::geometry_parameters() const {
  std::vector<GeometryGroup> groups = ideal_.geometry_parameters();
  std::array<Eigen::Vector3d, 6> offset1, offset2, strut_offset;
  for (int j = 0; j < 6; ++j) {
    offset1[j] = joints_[j].offset1_mm;
    offset2[j] = joints_[j].offset2_mm;
    strut_offset[j] = joints_[j].strut_offset_mm;
  }
  groups.push_back(point_group("cardan_offset1", "R'", offset1.data(), 6));
  groups.push_back(point_group("cardan_offset2", "R''", offset2.data(), 6));
  groups.push_back(point_group("cardan_strut_offset", "R*", strut_offset.data(), 6));
  return groups;
}

Result<std::unique_ptr<Mechanism>> HexapodRefined::with_geometry(
    const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  HexapodGeometry geometry;
  std::array<CardanJoint, 6> joints = joints_;  // the axes are kept
  for (int j = 0; j < 6; ++j) {
    geometry.base_joints_mm[j] = group_point(groups[0], j);
    geometry.platform_joints_mm[j] = group_point(groups[1], j);
    joints[j].offset1_mm = group_point(groups[2], j);
    joints[j].offset2_mm = group_point(groups[3], j);
    joints[j].strut_offset_mm = group_point(groups[4], j);
  }
  return std::unique_ptr<Mechanism>(std::make_unique<HexapodRefined>(geometry, joints, convention_, home_));
}

}  // namespace pkm
