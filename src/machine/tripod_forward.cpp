// Forward kinematics of the 3-RPS tripod in the joint-angle form of Smirnov 2019, §2.3.4. Every joint angle
// t_j keeps B_j on its strut's circle, so (29) and (31) hold exactly and only the three rigid distances (30)
// remain: three equations in (t_1, t_2, t_3), solved by damped Newton from the guess's joint angles. The pose
// then follows from the three joint points (Eigen::umeyama, exact for a rigid triangle).
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "kinematics/damped_newton.hpp"
#include "machine/tripod.hpp"

namespace pkm {

Eigen::Vector3d Tripod::joint_at(int j, double length_mm, double angle_rad) const noexcept {
  return geometry_.base_joints_mm[j] +
         length_mm * (std::cos(angle_rad) * Eigen::Vector3d::UnitZ() + std::sin(angle_rad) * plane_side_[j]);
}

double Tripod::joint_angle_of(int j, const Eigen::Vector3d& point_mm) const noexcept {
  const Eigen::Vector3d d = point_mm - geometry_.base_joints_mm[j];
  return std::atan2(plane_side_[j].dot(d), Eigen::Vector3d::UnitZ().dot(d));
}

Pose Tripod::pose_from_joints(const std::array<Eigen::Vector3d, 3>& joints_mm) const noexcept {
  Eigen::Matrix3d from, to;
  for (int j = 0; j < 3; ++j) {
    from.col(j) = geometry_.platform_joints_mm[j];
    to.col(j) = joints_mm[j];
  }
  const Eigen::Matrix4d t = Eigen::umeyama(from, to, false);
  Pose pose;
  pose.rotation = t.topLeftCorner<3, 3>();
  pose.position_mm = t.topRightCorner<3, 1>();
  return pose;
}

void Tripod::distance_equations(const Eigen::Vector3d& l, const Eigen::Vector3d& t, Eigen::Vector3d& f,
                                Eigen::Matrix3d& df_dt) const noexcept {
  // f_k = |B_i − B_k|² − d_ik² with B_j(t_j) from the joint-angle form (§2.3.4); pairs k = (1,2), (2,3),
  // (3,1).
  std::array<Eigen::Vector3d, 3> b, db;
  for (int j = 0; j < 3; ++j) {
    b[j] = joint_at(j, l[j], t[j]);
    db[j] = l[j] * (-std::sin(t[j]) * Eigen::Vector3d::UnitZ() + std::cos(t[j]) * plane_side_[j]);
  }
  df_dt.setZero();
  for (int k = 0; k < 3; ++k) {
    const int i = k, n = (k + 1) % 3;
    const Eigen::Vector3d d = b[i] - b[n];
    f[k] = d.squaredNorm() - platform_distance_mm_[k] * platform_distance_mm_[k];
    df_dt(k, i) = 2.0 * d.dot(db[i]);
    df_dt(k, n) = -2.0 * d.dot(db[n]);
  }
}

Result<FkSolution> Tripod::forward(const ActuatorVector& q, const Pose& guess,
                                   const FkOptions& options) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("a tripod needs 3 strut lengths, got {}", q.size()));
  }
  const Eigen::Vector3d l = q.head<3>();
  for (int j = 0; j < 3; ++j) {
    if (!(l[j] > 0.0))
      return make_error(ErrorCode::bad_input, fmt::format("strut {} length must be positive", j + 1));
  }
  // Quick reach test: B_i and B_k lie on circles of radii L_i, L_k about A_i, A_k.
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    const double base = (geometry_.base_joints_mm[n] - geometry_.base_joints_mm[k]).norm();
    const double d = platform_distance_mm_[k];
    if (d > base + l[k] + l[n] || d < base - l[k] - l[n]) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("struts {} and {} cannot hold their platform joints {:.3f} mm apart", k + 1, n + 1, d));
    }
  }

  Eigen::Vector3d start;
  for (int j = 0; j < 3; ++j) start[j] = joint_angle_of(j, guess.to_base(geometry_.platform_joints_mm[j]));
  // |f_k| / (2 d_k) is, to first order, the error of the distance |B_i B_k| in mm.
  const Eigen::Vector3d to_mm(0.5 / platform_distance_mm_[0], 0.5 / platform_distance_mm_[1],
                              0.5 / platform_distance_mm_[2]);
  auto equations = [&](const Eigen::Vector3d& angles, Eigen::Vector3d& f, Eigen::Matrix3d& df) {
    distance_equations(l, angles, f, df);
    return true;
  };
  NewtonState<3> state;
  switch (damped_newton<3>(equations, start, to_mm, options, state)) {
    case NewtonStatus::converged:
      break;
    case NewtonStatus::start_outside:  // distance_equations is defined everywhere
    case NewtonStatus::not_converged:
      return make_error(
          ErrorCode::not_converged,
          fmt::format("forward kinematics did not converge within {} iterations (residual {:.3g} mm); "
                      "give a guess closer to the solution",
                      options.max_iterations, state.residual_mm));
    case NewtonStatus::singular_on_the_way:
      return make_error(ErrorCode::singular,
                        "forward kinematics: the joint-angle Jacobian is singular on the way to a solution "
                        "(the strut lengths may lie at a singular configuration)");
    case NewtonStatus::singular_at_solution:
      return make_error(ErrorCode::singular,
                        "forward kinematics: these strut lengths put the tripod in a singular configuration");
  }
  const Eigen::Vector3d t = state.x;
  const int iteration = state.iterations;
  std::array<Eigen::Vector3d, 3> joints;
  for (int j = 0; j < 3; ++j) joints[j] = joint_at(j, l[j], t[j]);
  FkSolution solution;
  solution.pose = pose_from_joints(joints);
  solution.iterations = iteration;
  solution.residual_mm = (strut_lengths(solution.pose) - l).cwiseAbs().maxCoeff();
  const int mode = assembly_mode(solution.pose, l);
  solution.branch = mode == home_mode_ ? 0 : mode + 1;
  // The guess's mode is judged at the start of the iteration: its joint angles with the target lengths.
  if (options.require_same_branch && mode != assembly_mode(guess, l)) {
    return another_assembly_mode_error(solution.pose);
  }
  return solution;
}

}  // namespace pkm
