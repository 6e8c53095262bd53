#include "machine/hexapod.hpp"

#include <fmt/format.h>

#include <Eigen/LU>

#include "kinematics/coordinate_jacobian.hpp"
#include "kinematics/platform_newton.hpp"

namespace pkm {

Hexapod::Hexapod(const HexapodGeometry& geometry, AngleConvention convention, const Pose& home)
    : geometry_(geometry),
      convention_(convention),
      base_plane_(geometry.base_joints_mm, geometry.platform_joints_mm, home) {
  home_ = home;
  for (int j = 0; j < 6; ++j) {
    layout_.platform_mm.col(j) = geometry_.platform_joints_mm[j];
    layout_.base_mm.col(j) = geometry_.base_joints_mm[j];
  }
  home_determinant_ = twist_jacobian(home_).determinant();
  home_mode_ = assembly_mode(home_);

  int merged_pairs = 0;
  for (int j = 0; j < 6; ++j) {
    for (int k = j + 1; k < 6; ++k) {
      if ((geometry_.platform_joints_mm[j] - geometry_.platform_joints_mm[k]).norm() < 1e-9) ++merged_pairs;
    }
  }
  six_three_ = merged_pairs == 3;
}

Eigen::Matrix<double, 6, 6> Hexapod::twist_jacobian(const Pose& pose) const noexcept {
  Eigen::Matrix<double, 6, 6> j;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d arm = pose.rotation * geometry_.platform_joints_mm[i];
    const Eigen::Vector3d unit = (arm + pose.position_mm - geometry_.base_joints_mm[i]).normalized();
    j.block<1, 3>(i, 0) = unit.transpose();
    j.block<1, 3>(i, 3) = arm.cross(unit).transpose();
  }
  return j;
}

int Hexapod::assembly_mode(const Pose& pose) const {
  return assembly_mode(pose, twist_jacobian(pose).determinant());
}

int Hexapod::assembly_mode(const Pose& pose, double det) const {
  return base_plane_.assembly_mode(pose, geometry_.platform_joints_mm, det);
}

Result<ActuatorVector> Hexapod::inverse(const Pose& pose) const {
  ActuatorVector lengths(6);
  strut_lengths(pose, lengths.data());
  for (int j = 0; j < 6; ++j) {
    if (!(lengths[j] > 0.0)) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("strut {} would have zero length: platform joint on its base joint", j + 1));
    }
  }
  return lengths;
}

Result<FkSolution> Hexapod::forward(const ActuatorVector& actuators, const Pose& guess,
                                    const FkOptions& options) const {
  PlatformFkWorkspace<6> fresh;
  return forward(actuators, guess, options, fresh);
}

Result<FkSolution> Hexapod::forward(const ActuatorVector& actuators, const Pose& guess,
                                    const FkOptions& options, PlatformFkWorkspace<6>& workspace) const {
  if (actuators.size() != 6) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("a hexapod needs 6 strut lengths, got {}", actuators.size()));
  }
  FkSolution solution;
  PlatformFkFailure failure;
  bool other_mode = false;
  if (forward_quiet(actuators, guess, options, workspace, solution, failure, other_mode)) return solution;
  if (other_mode) return another_assembly_mode_error(solution.pose);
  return detail::platform_fk_error(failure, options);
}

bool Hexapod::forward_quiet(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                            PlatformFkWorkspace<6>& workspace, FkSolution& out, PlatformFkFailure& failure,
                            bool& other_mode) const {
  other_mode = false;
  FkDiagnostics diagnostics;
  // The guess's mode is known when it is the previous solution on this path.
  const int known_guess_mode = workspace.continues_path(guess) ? workspace.last_solution_mode : -1;
  if (!detail::solve_platform_fk_quiet<6>(*this, actuators, guess, options, &diagnostics, &workspace, out,
                                          failure)) {
    return false;
  }
  // The determinants come from the solver's own factorisations (at the guess, and one converging step before
  // the solution), so the check costs only the side-of-base test.
  // Near a singularity the last factorisation (one step before the solution) may sit on the other side of it:
  // when its |det J| is below 1 % of the home pose's, the sign is taken at the solution itself.
  constexpr double kTrustedDeterminantFraction = 1e-2;
  const double determinant =
      std::abs(diagnostics.final_determinant) >= kTrustedDeterminantFraction * std::abs(home_determinant_)
          ? diagnostics.final_determinant
          : twist_jacobian(out.pose).determinant();
  const int mode = assembly_mode(out.pose, determinant);
  out.branch = mode == home_mode_ ? 0 : mode + 1;
  workspace.last_solution_mode = mode;
  const int guess_mode =
      known_guess_mode >= 0 ? known_guess_mode : assembly_mode(guess, diagnostics.guess_determinant);
  if (options.require_same_branch && mode != guess_mode) {
    workspace.reset();
    other_mode = true;
    return false;
  }
  return true;
}

Result<FkSolution> Hexapod::forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                         const FkOptions& options, FkWorkspace& workspace) const {
  // The owner check makes the downcast safe: only this hexapod's make_fk_workspace made such a workspace.
  if (workspace.owner() != this) return forward(actuators, guess, options);
  return forward(actuators, guess, options, static_cast<HexapodFkWorkspace&>(workspace).platform);
}

bool Hexapod::forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                                 FkWorkspace& workspace, FkSolution& out, ErrorCode& failure) const {
  if (workspace.owner() != this || actuators.size() != 6) {
    return Mechanism::forward_warm_quiet(actuators, guess, options, workspace, out, failure);
  }
  PlatformFkFailure reason;
  bool other_mode = false;
  if (forward_quiet(actuators, guess, options, static_cast<HexapodFkWorkspace&>(workspace).platform, out,
                    reason, other_mode)) {
    return true;
  }
  failure = other_mode ? ErrorCode::wrong_branch : reason.code();
  return false;
}

std::unique_ptr<FkWorkspace> Hexapod::make_fk_workspace() const {
  return std::make_unique<HexapodFkWorkspace>(this);
}

bool Hexapod::actuator_values(const Pose& pose, double* out) const noexcept {
  return six_strut_lengths(layout_, pose, out);  // false for a zero (or NaN) length, as inverse()
}

bool Hexapod::actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                                 double* out) const noexcept {
  return six_strut_lengths_at(layout_, convention, coordinates, out);  // the same bits, without a Pose
}

int Hexapod::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  for (int j = 0; j < 6; ++j) {
    out.base_mm[j] = geometry_.base_joints_mm[j];
    out.platform_mm[j] = pose.to_base(geometry_.platform_joints_mm[j]);
  }
  out.platform_rotation = pose.rotation;
  out.mounts_turn = false;
  return 6;
}

int Hexapod::strut_state(const Pose& pose, StrutJointPoints& ends, double* actuators,
                         JacobianMatrix& twist_rows) const noexcept {
  // All six struts at once: each quantity a row of six values. The lengths by the same operations, in the
  // same order, as actuator_values() (kinematics/strut_lengths.cpp), so the same bits: the dynamics take a
  // strut's force from its length against the rest length actuator_values() gave; the twist rows as
  // twist_jacobian() makes them strut by strut, to rounding (tests/machine/twist_jacobian_test.cpp).
  using Lanes = Eigen::Array<double, 1, 6>;
  const Eigen::Matrix3d& r = pose.rotation;
  const Lanes px = layout_.platform_mm.row(0).head<6>().array(),
              py = layout_.platform_mm.row(1).head<6>().array(),
              pz = layout_.platform_mm.row(2).head<6>().array();
  const Lanes arm_x = r(0, 0) * px + r(0, 1) * py + r(0, 2) * pz;  // R b_j: the joint from the tool point
  const Lanes arm_y = r(1, 0) * px + r(1, 1) * py + r(1, 2) * pz;
  const Lanes arm_z = r(2, 0) * px + r(2, 1) * py + r(2, 2) * pz;
  const Lanes joint_x = arm_x + pose.position_mm.x(), joint_y = arm_y + pose.position_mm.y(),
              joint_z = arm_z + pose.position_mm.z();
  const Lanes ox = pose.position_mm.x() - layout_.base_mm.row(0).head<6>().array(),
              oy = pose.position_mm.y() - layout_.base_mm.row(1).head<6>().array(),
              oz = pose.position_mm.z() - layout_.base_mm.row(2).head<6>().array();
  const Lanes dx = (r(0, 0) * px + r(0, 1) * py) + (r(0, 2) * pz + ox);
  const Lanes dy = (r(1, 0) * px + r(1, 1) * py) + (r(1, 2) * pz + oy);
  const Lanes dz = (r(2, 0) * px + r(2, 1) * py) + (r(2, 2) * pz + oz);
  const Lanes length = (dx * dx + dy * dy + dz * dz).sqrt();
  if (!(length > 0.0).all()) return -1;  // as actuator_values()
  const Lanes ux = dx / length, uy = dy / length, uz = dz / length;
  twist_rows.resize(6, 6);
  // Written through a fixed-size view of the storage just sized: columns without run-time size logic.
  Eigen::Map<Eigen::Matrix<double, 6, 6>> rows(twist_rows.data());
  rows.col(0) = ux.transpose();
  rows.col(1) = uy.transpose();
  rows.col(2) = uz.transpose();
  rows.col(3) = (arm_y * uz - arm_z * uy).transpose();  // arm × u
  rows.col(4) = (arm_z * ux - arm_x * uz).transpose();
  rows.col(5) = (arm_x * uy - arm_y * ux).transpose();
  for (int j = 0; j < 6; ++j) {
    ends.base_mm[j] = geometry_.base_joints_mm[j];
    ends.platform_mm[j] = Eigen::Vector3d(joint_x[j], joint_y[j], joint_z[j]);
    actuators[j] = length[j];
  }
  ends.platform_rotation = pose.rotation;
  ends.mounts_turn = false;
  return 6;
}

Result<JacobianMatrix> Hexapod::jacobian(const Pose& pose) const {
  const JacobianMatrix twist = twist_jacobian(pose);
  return coordinate_jacobian(twist, convention_, angles_from_rotation(convention_, pose.rotation),
                             AxisMask::all());
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Hexapod::geometry_parameters() const {
  return {point_group("base_joints", "A", geometry_.base_joints_mm.data(), 6),
          point_group("platform_joints_from_tool", "B", geometry_.platform_joints_mm.data(), 6)};
}

Result<std::unique_ptr<Mechanism>> Hexapod::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  HexapodGeometry geometry;
  for (int j = 0; j < 6; ++j) {
    geometry.base_joints_mm[j] = group_point(groups[0], j);
    geometry.platform_joints_mm[j] = group_point(groups[1], j);
  }
  return std::unique_ptr<Mechanism>(std::make_unique<Hexapod>(geometry, convention_, home_));
}

}  // namespace pkm
