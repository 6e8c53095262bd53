#include "machine/planar2.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

namespace pkm {
namespace {

Eigen::Vector2d point_of(const Pose& pose) {
  return pose.position_mm.head<2>();
}

Pose pose_of(const Eigen::Vector2d& b_mm) {
  Pose pose;
  pose.position_mm << b_mm.x(), b_mm.y(), 0.0;
  return pose;
}

}  // namespace

Planar2::Planar2(const Planar2Geometry& geometry, const Eigen::Vector2d& home_mm) : geometry_(geometry) {
  const Eigen::Vector2d a1a2 = geometry_.base_joints_mm[1] - geometry_.base_joints_mm[0];
  base_distance_mm_ = a1a2.norm();
  along_ = a1a2 / base_distance_mm_;
  normal_ = Eigen::Vector2d(-along_.y(), along_.x());
  home_ = pose_of(home_mm);
  home_side_ = side_mm(home_mm) >= 0.0 ? 1 : -1;
}

double Planar2::jacobian_determinant(const Eigen::Vector2d& b_mm) const noexcept {
  const Eigen::Vector2d u1 = (b_mm - geometry_.base_joints_mm[0]).normalized();
  const Eigen::Vector2d u2 = (b_mm - geometry_.base_joints_mm[1]).normalized();
  return u1.x() * u2.y() - u1.y() * u2.x();
}

Result<Pose> Planar2::complete_pose(const Pose& pose) const {
  return pose_of(point_of(pose));
}

Result<ActuatorVector> Planar2::inverse(const Pose& pose) const {
  ActuatorVector lengths(2);
  strut_lengths(point_of(pose), lengths.data());
  for (int j = 0; j < 2; ++j) {
    if (!(lengths[j] > 0.0)) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("strut {} would have zero length: B on its base joint A{}", j + 1, j + 1));
    }
  }
  return lengths;
}

bool Planar2::actuator_values(const Pose& pose, double* out) const noexcept {
  strut_lengths(point_of(pose), out);
  return out[0] > 0.0 && out[1] > 0.0;
}

bool Planar2::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  const Eigen::Vector2d b = point_of(pose);
  out.setZero(2, 6);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d strut = b - geometry_.base_joints_mm[i];
    const double length_mm = strut.norm();
    if (!(length_mm > 0.0)) return false;
    out.block<1, 2>(i, 0) = strut.transpose() / length_mm;
  }
  return true;
}

int Planar2::strut_ends(const Pose& pose, StrutJointPoints& out) const {
  for (int j = 0; j < 2; ++j) {
    const Eigen::Vector2d& a = geometry_.base_joints_mm[j];
    out.base_mm[j] = Eigen::Vector3d(a.x(), a.y(), 0.0);
    out.platform_mm[j] = pose.position_mm;
  }
  out.platform_rotation = pose.rotation;
  out.mounts_turn = false;
  return 2;
}

Result<JacobianMatrix> Planar2::jacobian(const Pose& pose) const {
  const Eigen::Vector2d b = point_of(pose);
  JacobianMatrix j(2, 2);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d strut = b - geometry_.base_joints_mm[i];
    const double length_mm = strut.norm();
    if (!(length_mm > 0.0)) {
      return make_error(
          ErrorCode::singular,
          fmt::format("strut {} has zero length (B on A{}): its direction is undefined", i + 1, i + 1));
    }
    // Eq. (4) with the sign corrected (printed with the opposite sign): dL_j/dB = (B − A_j)/L_j.
    j.row(i) = strut.transpose() / length_mm;
  }
  return j;
}

Result<Eigen::Vector2d> Planar2::intersect(const ActuatorVector& q, int side,
                                           const FkOptions& options) const {
  const double l1 = q[0], l2 = q[1], d = base_distance_mm_;
  if (!(l1 > 0.0 && l2 > 0.0)) {
    return make_error(ErrorCode::unreachable,
                      fmt::format("strut lengths must be positive: L1 = {:.6f} mm, L2 = {:.6f} mm", l1, l2));
  }
  if (l1 + l2 < d || std::abs(l1 - l2) > d) {
    return make_error(
        ErrorCode::unreachable,
        fmt::format("the struts cannot meet: L1 = {:.6f} mm, L2 = {:.6f} mm, |A1A2| = {:.6f} mm "
                    "(needs |L1 - L2| <= |A1A2| <= L1 + L2)",
                    l1, l2, d));
  }
  // Circle–circle intersection in the frame (A_1; along_, normal_): the general-frame form of eq. (5)/(6).
  // The height h uses Heron's product, which stays accurate near the singular (flat) triangle where the
  // textbook L_1² − a² cancels.
  const double along_mm = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
  const double heron = (l1 + l2 + d) * (-l1 + l2 + d) * (l1 - l2 + d) * (l1 + l2 - d);
  const double height_mm = std::sqrt(std::fmax(heron, 0.0)) / (2.0 * d);
  Eigen::Vector2d b = geometry_.base_joints_mm[0] + along_mm * along_ + side * height_mm * normal_;

  // D = 0 (B on line A_1A_2, eq. 7 and 78): both solutions merge and B's velocity is undetermined.
  Eigen::Matrix2d j;
  for (int i = 0; i < 2; ++i) j.row(i) = (b - geometry_.base_joints_mm[i]).normalized().transpose();
  const Eigen::PartialPivLU<Eigen::Matrix2d> lu(j);
  if (!(lu.rcond() >= options.min_rcond)) {
    return make_error(ErrorCode::singular,
                      fmt::format("L1 = {:.6f} mm, L2 = {:.6f} mm put B on line A1A2 (|A1A2| = {:.6f} mm): "
                                  "a singular configuration (D = 0)",
                                  l1, l2, d));
  }
  return b;
}

Result<FkSolution> Planar2::solution_at(const ActuatorVector& q, int side, const FkOptions& options) const {
  auto b = intersect(q, side, options);
  if (!b) return b.error();
  // The closed form is exact up to rounding; a few Newton steps (eq. 4 Jacobian) only matter when rounding of
  // the closed form exceeds a very tight tolerance.
  FkSolution solution;
  Eigen::Vector2d lengths;
  for (int iteration = 0;; ++iteration) {
    strut_lengths(*b, lengths.data());
    const Eigen::Vector2d residual = lengths - q.head<2>();
    solution.residual_mm = residual.cwiseAbs().maxCoeff();
    solution.iterations = iteration;
    if (solution.residual_mm <= options.tolerance_mm) break;
    if (iteration == options.max_iterations) {
      return make_error(ErrorCode::not_converged,
                        fmt::format("forward kinematics: residual {:.3e} mm above the tolerance {:.3e} mm "
                                    "(B is nearly on line A1A2)",
                                    solution.residual_mm, options.tolerance_mm));
    }
    Eigen::Matrix2d j;
    for (int i = 0; i < 2; ++i) j.row(i) = (*b - geometry_.base_joints_mm[i]).transpose() / lengths[i];
    *b -= j.partialPivLu().solve(residual);
  }
  solution.pose = pose_of(*b);
  solution.branch = side == home_side_ ? 0 : 1;
  return solution;
}

Result<FkSolution> Planar2::forward(const ActuatorVector& actuators, const Pose& guess,
                                    const FkOptions& options) const {
  if (actuators.size() != 2) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("planar2 needs 2 strut lengths, got {}", actuators.size()));
  }
  // The assembly mode is the side of line A_1A_2 (source: "B above A_1A_2"); the closed form picks the
  // guess's side directly, so the solution is always in the guess's mode (require_same_branch holds by
  // construction).
  const double guess_side_mm = side_mm(point_of(guess));
  const int side = guess_side_mm > 0.0 ? 1 : (guess_side_mm < 0.0 ? -1 : home_side_);
  return solution_at(actuators, side, options);
}

Result<std::vector<FkSolution>> Planar2::forward_all(const ActuatorVector& actuators,
                                                     const FkOptions& options) const {
  if (actuators.size() != 2) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("planar2 needs 2 strut lengths, got {}", actuators.size()));
  }
  std::vector<FkSolution> solutions;
  for (int side : {home_side_, -home_side_}) {
    auto solution = solution_at(actuators, side, options);
    if (!solution) return solution.error();
    solutions.push_back(*solution);
  }
  return solutions;
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Planar2::geometry_parameters() const {
  GeometryGroup base{"base_joints", "A", {"x", "y"}, "mm", 2, {}};
  for (const Eigen::Vector2d& a : geometry_.base_joints_mm)
    base.values.insert(base.values.end(), {a.x(), a.y()});
  return {base};
}

Result<std::unique_ptr<Mechanism>> Planar2::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  Planar2Geometry geometry;
  const std::vector<double>& v = groups[0].values;
  for (std::size_t j = 0; j < 2; ++j) geometry.base_joints_mm[j] = Eigen::Vector2d(v[2 * j], v[2 * j + 1]);
  if (!((geometry.base_joints_mm[1] - geometry.base_joints_mm[0]).norm() > 0.0)) {
    return make_error(ErrorCode::bad_input, "base joints A1 and A2 coincide");
  }
  return std::unique_ptr<Mechanism>(std::make_unique<Planar2>(geometry, home_.position_mm.head<2>()));
}

}  // namespace pkm
