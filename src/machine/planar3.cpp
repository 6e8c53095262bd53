#include "machine/planar3.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "core/units.hpp"

namespace pkm {
namespace {

/// A guess whose |normalized det J| is below this sits on a singularity: its assembly mode is undefined, so
/// the same-branch rule cannot be applied to it (dimensionless; rounding of det J is ~1e-16).
constexpr double kSingularGuessDeterminant = 1e-9;
/// Step halvings of the backtracking line search before the iteration gives up (step ≥ 2⁻³⁰ of Newton's).
constexpr int kPlanar3MaxHalvings = 30;

Eigen::Matrix2d rotation_2d(double phi_rad) {
  const double c = std::cos(phi_rad), s = std::sin(phi_rad);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

}  // namespace

Eigen::Vector3d planar_coordinates(const Pose& pose) {
  return {pose.position_mm.x(), pose.position_mm.y(), std::atan2(pose.rotation(1, 0), pose.rotation(0, 0))};
}

Pose pose_from_planar(const Eigen::Vector3d& xyphi) {
  Pose pose;
  pose.position_mm << xyphi.x(), xyphi.y(), 0.0;
  pose.rotation = rot_z(xyphi.z());
  return pose;
}

Planar3::Planar3(const Planar3Geometry& geometry, const Eigen::Vector3d& home) : geometry_(geometry) {
  double radius_mm = 0.0;
  for (const auto& b : geometry_.platform_joints_mm) radius_mm = std::fmax(radius_mm, b.norm());
  platform_radius_mm_ = radius_mm > 0.0 ? radius_mm : 1.0;
  home_ = pose_from_planar(home);
  home_sign_ = determinant_sign(home) < 0 ? -1 : 1;
}

void Planar3::strut_lengths(const Eigen::Vector3d& xyphi, double* lengths_mm) const noexcept {
  const Eigen::Matrix2d r = rotation_2d(xyphi.z());
  for (int j = 0; j < 3; ++j) {
    // Eq. (8)/(79): B_j = R(φ) b'_j + C.
    lengths_mm[j] =
        (r * geometry_.platform_joints_mm[j] + xyphi.head<2>() - geometry_.base_joints_mm[j]).norm();
  }
}

Eigen::Matrix3d Planar3::planar_jacobian(const Eigen::Vector3d& xyphi) const noexcept {
  const Eigen::Matrix2d r = rotation_2d(xyphi.z());
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d arm = r * geometry_.platform_joints_mm[i];  // (r_x, r_y) of eq. (80)
    const Eigen::Vector2d strut = arm + xyphi.head<2>() - geometry_.base_joints_mm[i];
    const double length_mm = strut.norm();
    if (!(length_mm > 0.0)) continue;
    const Eigen::Vector2d unit = strut / length_mm;
    // Eq. (80): ∂L/∂x_C, ∂L/∂y_C are the strut direction; ∂L/∂φ is the moment of the strut line about C,
    // (R b'_j) × u_j, which equals the printed [(x_A − x_C) r_y + (y_A − y_C)(−r_x)] / L_j.
    j(i, 0) = unit.x();
    j(i, 1) = unit.y();
    j(i, 2) = arm.x() * unit.y() - arm.y() * unit.x();
  }
  return j;
}

double Planar3::normalized_determinant(const Eigen::Vector3d& xyphi) const noexcept {
  Eigen::Matrix3d j = planar_jacobian(xyphi);
  j.col(2) /= platform_radius_mm_;
  return j.determinant();
}

int Planar3::determinant_sign(const Eigen::Vector3d& xyphi, double singular_below) const noexcept {
  const double det = normalized_determinant(xyphi);
  if (!(std::abs(det) > singular_below)) return 0;
  return det > 0.0 ? 1 : -1;
}

int Planar3::branch_of(const Eigen::Vector3d& xyphi) const noexcept {
  return determinant_sign(xyphi) == home_sign_ ? 0 : 1;
}

Result<Pose> Planar3::complete_pose(const Pose& pose) const {
  return pose_from_planar(planar_coordinates(pose));
}

Result<ActuatorVector> Planar3::inverse(const Pose& pose) const {
  ActuatorVector lengths(3);
  strut_lengths(planar_coordinates(pose), lengths.data());
  for (int j = 0; j < 3; ++j) {
    if (!(lengths[j] > 0.0)) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("strut {} would have zero length: platform joint on its base joint", j + 1));
    }
  }
  return lengths;
}

bool Planar3::actuator_values(const Pose& pose, double* out) const noexcept {
  strut_lengths(planar_coordinates(pose), out);
  return out[0] > 0.0 && out[1] > 0.0 && out[2] > 0.0;
}

bool Planar3::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  const Eigen::Vector3d xyphi = planar_coordinates(pose);
  double lengths_mm[3];
  strut_lengths(xyphi, lengths_mm);
  if (!(lengths_mm[0] > 0.0 && lengths_mm[1] > 0.0 && lengths_mm[2] > 0.0)) return false;
  const Eigen::Matrix3d planar = planar_jacobian(xyphi);
  out.setZero(3, 6);
  out.col(0) = planar.col(0);
  out.col(1) = planar.col(1);
  out.col(5) = planar.col(2);
  return true;
}

int Planar3::strut_ends(const Pose& pose, StrutJointPoints& out) const {
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector2d& a = geometry_.base_joints_mm[j];
    const Eigen::Vector2d& b = geometry_.platform_joints_mm[j];
    out.base_mm[j] = Eigen::Vector3d(a.x(), a.y(), 0.0);
    out.platform_mm[j] = pose.to_base(Eigen::Vector3d(b.x(), b.y(), 0.0));
  }
  out.platform_rotation = pose.rotation;
  out.mounts_turn = false;
  return 3;
}

Result<JacobianMatrix> Planar3::jacobian(const Pose& pose) const {
  const Eigen::Vector3d xyphi = planar_coordinates(pose);
  Eigen::Vector3d lengths;
  strut_lengths(xyphi, lengths.data());
  for (int j = 0; j < 3; ++j) {
    if (!(lengths[j] > 0.0)) {
      return make_error(ErrorCode::singular,
                        fmt::format("strut {} has zero length: its direction is undefined", j + 1));
    }
  }
  return JacobianMatrix(planar_jacobian(xyphi));
}

Result<FkSolution> Planar3::solve_from(const ActuatorVector& q, const Eigen::Vector3d& start,
                                       const FkOptions& options) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("planar3 needs 3 strut lengths, got {}", q.size()));
  }
  const Eigen::Vector3d target = q.head<3>();
  // Residual f = L(x, y, φ) − L_target; false when a strut would have zero length (direction undefined).
  auto evaluate = [&](const Eigen::Vector3d& xyphi, Eigen::Vector3d& residual) {
    Eigen::Vector3d lengths;
    strut_lengths(xyphi, lengths.data());
    residual = lengths - target;
    return (lengths.array() > 0.0).all();
  };
  Eigen::Vector3d x = start;
  Eigen::Vector3d f;
  if (!evaluate(x, f)) {
    return make_error(ErrorCode::unreachable,
                      "forward kinematics: the guess puts a platform joint on its base joint");
  }
  double norm = f.norm();
  for (int iteration = 0; iteration <= options.max_iterations; ++iteration) {
    // φ column in mm (divided by the platform radius) so that the condition number does not depend on units.
    Eigen::Matrix3d j = planar_jacobian(x);
    j.col(2) /= platform_radius_mm_;
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(j);
    const double rcond = lu.rcond();
    const double max_abs = f.cwiseAbs().maxCoeff();
    if (max_abs <= options.tolerance_mm) {
      // A solution at a singular configuration is reported, not returned: its neighbourhood is not unique.
      if (!(rcond >= options.min_rcond)) {
        return make_error(
            ErrorCode::singular,
            "forward kinematics: these strut lengths put the platform in a singular configuration");
      }
      return FkSolution{pose_from_planar(x), iteration, max_abs, 0};
    }
    if (iteration == options.max_iterations) break;
    if (!(rcond >= options.min_rcond)) {
      return make_error(ErrorCode::singular,
                        "forward kinematics: the Jacobian is singular on the way to a solution "
                        "(the strut lengths may lie at a singular configuration)");
    }
    Eigen::Vector3d step = lu.solve(-f);
    step.z() /= platform_radius_mm_;
    // Damping: halve the Newton step until |f| decreases, so that cold starts do not diverge.
    double fraction = 1.0;
    bool accepted = false;
    Eigen::Vector3d trial_f;
    for (int halving = 0; halving < kPlanar3MaxHalvings && !accepted; ++halving, fraction *= 0.5) {
      const Eigen::Vector3d trial = x + fraction * step;
      if (!evaluate(trial, trial_f)) continue;
      const double trial_norm = trial_f.norm();
      if (trial_norm < norm || trial_f.cwiseAbs().maxCoeff() <= options.tolerance_mm) {
        x = trial;
        f = trial_f;
        norm = trial_norm;
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  return make_error(
      ErrorCode::not_converged,
      fmt::format("forward kinematics did not converge within {} iterations (residual {:.3e} mm); "
                  "give a guess closer to the solution",
                  options.max_iterations, f.cwiseAbs().maxCoeff()));
}

Result<FkSolution> Planar3::forward(const ActuatorVector& actuators, const Pose& guess,
                                    const FkOptions& options) const {
  const Eigen::Vector3d start = planar_coordinates(guess);
  auto solution = solve_from(actuators, start, options);
  if (!solution) {
    // Newton cannot tell "no solution" from "bad guess"; the enumeration can (failure path only, may
    // allocate).
    const ErrorCode code = solution.error().code;
    if (code == ErrorCode::not_converged || code == ErrorCode::singular) {
      auto all = forward_all(actuators, options);
      if (!all && all.error().code == ErrorCode::unreachable) return all.error();
    }
    return solution;
  }
  const Eigen::Vector3d found = planar_coordinates(solution->pose);
  solution->branch = branch_of(found);
  const int guess_sign = determinant_sign(start, kSingularGuessDeterminant);
  if (options.require_same_branch && guess_sign != 0 && determinant_sign(found) != guess_sign) {
    return make_error(
        ErrorCode::wrong_branch,
        fmt::format("forward kinematics converged to another assembly mode than the guess's "
                    "(x={:.3f} y={:.3f} mm phi={:.3f} deg, det J changed sign); give a guess nearer "
                    "the wanted pose",
                    found.x(), found.y(), deg_from_rad(found.z())));
  }
  return solution;
}

}  // namespace pkm

namespace pkm {
namespace {

// Planar points as a group of [x, y] rows, mm.
GeometryGroup planar3_point_group(std::string key, std::string row_symbol,
                                  const std::array<Eigen::Vector2d, 3>& points) {
  GeometryGroup group{std::move(key), std::move(row_symbol), {"x", "y"}, "mm", 3, {}};
  for (const Eigen::Vector2d& p : points) group.values.insert(group.values.end(), {p.x(), p.y()});
  return group;
}

Eigen::Vector2d planar3_group_point(const GeometryGroup& group, std::size_t row) {
  return {group.values[2 * row], group.values[2 * row + 1]};
}

}  // namespace

std::vector<GeometryGroup> Planar3::geometry_parameters() const {
  return {planar3_point_group("base_joints", "A", geometry_.base_joints_mm),
          planar3_point_group("platform_joints_from_tool", "B", geometry_.platform_joints_mm)};
}

Result<std::unique_ptr<Mechanism>> Planar3::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  Planar3Geometry geometry;
  for (std::size_t j = 0; j < 3; ++j) {
    geometry.base_joints_mm[j] = planar3_group_point(groups[0], j);
    geometry.platform_joints_mm[j] = planar3_group_point(groups[1], j);
  }
  return std::unique_ptr<Mechanism>(std::make_unique<Planar3>(geometry, planar_coordinates(home_)));
}

}  // namespace pkm
