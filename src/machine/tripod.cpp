// Spatial 3-RPS tripod: construction and checks, pose completion on the revolute planes (31) in closed form,
// inverse kinematics (29) and the Jacobian by implicit differentiation. Forward kinematics:
// tripod_forward.cpp.
#include "machine/tripod.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "core/units.hpp"

namespace pkm {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

// Pose-vector index and sign of the yaw φ (R = Rz(φ)·T): abc C = φ; krylov R = Rz(−ψ)·…, so ψ = −φ.
int yaw_index(AngleConvention convention) {
  return convention == AngleConvention::krylov ? 3 : 5;
}
double yaw_sign(AngleConvention convention) {
  return convention == AngleConvention::krylov ? -1.0 : 1.0;
}

double wrap_angle(double angle_rad) {
  return std::remainder(angle_rad, 2.0 * kPi);
}

bool collinear(const std::array<Eigen::Vector3d, 3>& p) {
  const Eigen::Vector3d u = p[1] - p[0], v = p[2] - p[0];
  return !(u.cross(v).squaredNorm() > 1e-12 * u.squaredNorm() * v.squaredNorm()) || u.isZero() || v.isZero();
}

}  // namespace

Tripod::Tripod(const TripodGeometry& geometry, AngleConvention convention)
    : geometry_(geometry), convention_(convention) {
  Eigen::Matrix<double, 3, 2> m;
  for (int j = 0; j < 3; ++j) {
    plane_side_[j] = geometry_.base_axes[j].cross(kUp);
    m(j, 0) = geometry_.base_axes[j].x();
    m(j, 1) = geometry_.base_axes[j].y();
  }
  for (int k = 0; k < 3; ++k) {
    platform_distance_mm_[k] =
        (geometry_.platform_joints_mm[(k + 1) % 3] - geometry_.platform_joints_mm[k]).norm();
  }
  // (31) is l_j x + m_j y + (terms in φ) = a_j·A_j; the left null vector of [l m] removes x and y.
  null_ = m.col(0).cross(m.col(1));
  if (null_.norm() > 0.0) null_.normalize();
  const Eigen::Matrix2d normal = m.transpose() * m;
  if (std::abs(normal.determinant()) > 0.0) xy_solve_ = normal.inverse() * m.transpose();
  base_centroid_mm_ =
      (geometry_.base_joints_mm[0] + geometry_.base_joints_mm[1] + geometry_.base_joints_mm[2]) / 3.0;
  base_normal_ = (geometry_.base_joints_mm[1] - geometry_.base_joints_mm[0])
                     .cross(geometry_.base_joints_mm[2] - geometry_.base_joints_mm[0])
                     .normalized();
}

Result<Tripod> Tripod::create(const TripodGeometry& geometry, AngleConvention convention,
                              const PoseVector& home) {
  if (convention == AngleConvention::euler_zxz) {
    return make_error(ErrorCode::bad_input,
                      "a tripod needs abc or krylov angles: its controlled tilts must be separable from the "
                      "rotation about z, which euler_zxz angles are not");
  }
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d& a = geometry.base_axes[j];
    if (std::abs(a.norm() - 1.0) > 1e-9 || std::abs(a.z()) > 1e-9) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("revolute axis {} must be a horizontal unit vector (eq. 31)", j + 1));
    }
  }
  Tripod tripod(geometry, convention);
  if (!(tripod.null_.norm() > 0.5)) {
    return make_error(ErrorCode::bad_input,
                      "the three revolute axes are parallel: x and y would not be determined");
  }
  if (collinear(geometry.platform_joints_mm)) {
    return make_error(ErrorCode::bad_input, "the three platform joints are collinear");
  }
  if (collinear(geometry.base_joints_mm)) {
    return make_error(ErrorCode::bad_input, "the three base joints are collinear");
  }

  // Of the two yaw branches of (31), the machine keeps the one nearer the home's given yaw.
  const Eigen::Matrix3d tilt = tripod.tilt_of(home);
  const double wanted_yaw = yaw_sign(convention) * home[yaw_index(convention)];
  double best = 1e300;
  TripodDependents chosen;
  for (int branch : {-1, 1}) {
    TripodDependents d;
    if (!tripod.solve_dependents(tilt, branch, d)) continue;
    const double distance = std::abs(wrap_angle(d.yaw_rad - wanted_yaw));
    if (distance < best) {
      best = distance;
      chosen = d;
      tripod.yaw_branch_ = branch;
    }
  }
  if (!(best < 1e300)) {
    return make_error(ErrorCode::unreachable,
                      "no yaw angle satisfies the three revolute-plane constraints (31) at the home tilts");
  }
  tripod.home_ = tripod.pose_of(home, chosen);

  Eigen::Vector3d platform_centroid = Eigen::Vector3d::Zero();
  for (const auto& b : geometry.platform_joints_mm) platform_centroid += tripod.home_.to_base(b) / 3.0;
  if (tripod.base_normal_.dot(platform_centroid - tripod.base_centroid_mm_) < 0) {
    tripod.base_normal_ = -tripod.base_normal_;
  }
  auto lengths = tripod.inverse(tripod.home_);
  if (!lengths) return lengths.error();
  if (auto j = tripod.jacobian(tripod.home_); !j) return j.error();
  Eigen::Vector3d angles, f;
  Eigen::Matrix3d df;
  for (int j = 0; j < 3; ++j)
    angles[j] = tripod.joint_angle_of(j, tripod.home_.to_base(geometry.platform_joints_mm[j]));
  tripod.distance_equations(lengths->head<3>(), angles, f, df);
  if (!(Eigen::PartialPivLU<Eigen::Matrix3d>(df).rcond() > 1e-9)) {
    return make_error(ErrorCode::singular,
                      "the tripod is at a forward-kinematics singularity in its home pose");
  }
  tripod.home_mode_ = tripod.assembly_mode(tripod.home_, lengths->head<3>());
  return tripod;
}

AxisMask Tripod::controlled_axes() const {
  if (convention_ == AngleConvention::krylov) return {{false, false, true, false, true, true}};
  return {{false, false, true, true, true, false}};
}

Eigen::Matrix3d Tripod::tilt_of(const PoseVector& coordinates) const {
  Eigen::Vector3d angles = coordinates.tail<3>();
  angles[yaw_index(convention_) - 3] = 0.0;
  return rotation_from_angles(convention_, angles);
}

Pose Tripod::pose_of(PoseVector coordinates, const TripodDependents& d) const {
  coordinates[0] = d.x_mm;
  coordinates[1] = d.y_mm;
  coordinates[yaw_index(convention_)] = yaw_sign(convention_) * d.yaw_rad;
  return pose_from_vector(convention_, coordinates);
}

Eigen::Vector3d Tripod::yaw_equation(const Eigen::Matrix3d& tilt) const noexcept {
  // a_j·(p + Rz(φ)·c_j − A_j) = 0 with c_j = T·b'_j and a_j = (l_j, m_j, 0):
  //   l_j x + m_j y + P_j cos φ + Q_j sin φ = a_j·A_j,  P_j = l c_x + m c_y,  Q_j = m c_x − l c_y.
  Eigen::Vector3d p, q, r;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d c = tilt * geometry_.platform_joints_mm[j];
    const Eigen::Vector3d& a = geometry_.base_axes[j];
    p[j] = a.x() * c.x() + a.y() * c.y();
    q[j] = a.y() * c.x() - a.x() * c.y();
    r[j] = a.dot(geometry_.base_joints_mm[j]);
  }
  return {null_.dot(p), null_.dot(q), null_.dot(r)};
}

bool Tripod::solve_dependents(const Eigen::Matrix3d& tilt, int branch, TripodDependents& out) const noexcept {
  // (31) is linear in (x, y, cos φ, sin φ): eliminating x, y leaves α cos φ + β sin φ = γ, solved in closed
  // form (two branches φ = atan2(β, α) ± acos(γ/√(α²+β²))); x, y then follow linearly.
  const Eigen::Vector3d abg = yaw_equation(tilt);
  const double amplitude = std::hypot(abg[0], abg[1]);
  if (!(amplitude > 0.0) || std::abs(abg[2]) > amplitude * (1.0 + 1e-12)) return false;
  const double delta = std::acos(std::fmax(-1.0, std::fmin(1.0, abg[2] / amplitude)));
  out.yaw_rad = wrap_angle(std::atan2(abg[1], abg[0]) + branch * delta);
  const double c = std::cos(out.yaw_rad), s = std::sin(out.yaw_rad);
  Eigen::Vector3d rhs;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d& a = geometry_.base_axes[j];
    const Eigen::Vector3d cj = tilt * geometry_.platform_joints_mm[j];
    rhs[j] = a.dot(geometry_.base_joints_mm[j]) - (a.x() * cj.x() + a.y() * cj.y()) * c -
             (a.y() * cj.x() - a.x() * cj.y()) * s;
  }
  const Eigen::Vector2d xy = xy_solve_ * rhs;
  out.x_mm = xy.x();
  out.y_mm = xy.y();
  return true;
}

int Tripod::yaw_branch_of(const Pose& pose) const noexcept {
  // φ = atan2(β, α) + s·δ  ⇔  s = sign(α sin φ − β cos φ).
  const Eigen::Matrix3d tilt = tilt_of(vector_from_pose(convention_, pose));
  const Eigen::Matrix3d yaw = pose.rotation * tilt.transpose();
  const double phi = std::atan2(yaw(1, 0), yaw(0, 0));
  const Eigen::Vector3d abg = yaw_equation(tilt);
  return abg[0] * std::sin(phi) - abg[1] * std::cos(phi) >= 0 ? 1 : -1;
}

int Tripod::assembly_mode(const Pose& pose, const Eigen::Vector3d& lengths_mm) const noexcept {
  // Side of the base plane (all platform joints above / below / mixed), sign of the FK Jacobian ∂f/∂t (its
  // zero set separates the assembly modes) and the yaw branch of (31).
  bool all_above = true, all_below = true;
  Eigen::Vector3d angles;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d b = pose.to_base(geometry_.platform_joints_mm[j]);
    const double side = base_normal_.dot(b - base_centroid_mm_);
    all_above = all_above && side > 0;
    all_below = all_below && side < 0;
    angles[j] = joint_angle_of(j, b);
  }
  Eigen::Vector3d f;
  Eigen::Matrix3d df;
  distance_equations(lengths_mm, angles, f, df);
  const int side = all_above ? 0 : (all_below ? 1 : 2);
  return 4 * side + (df.determinant() < 0 ? 2 : 0) + (yaw_branch_of(pose) < 0 ? 1 : 0);
}

Result<Pose> Tripod::complete_pose(const Pose& pose) const {
  const PoseVector c = vector_from_pose(convention_, pose);
  TripodDependents d;
  if (!solve_dependents(tilt_of(c), yaw_branch_, d)) {
    const auto names = pose_coordinate_names(*this);
    const int first = convention_ == AngleConvention::krylov ? 4 : 3;
    return make_error(
        ErrorCode::unreachable,
        fmt::format("no yaw satisfies the three revolute-plane constraints (31) at {}={:.4f} deg, "
                    "{}={:.4f} deg: the tilt is out of reach",
                    names[first], deg_from_rad(c[first]), names[first + 1], deg_from_rad(c[first + 1])));
  }
  return pose_of(c, d);
}

Eigen::Vector3d Tripod::strut_lengths(const Pose& pose) const noexcept {
  Eigen::Vector3d l;
  for (int j = 0; j < 3; ++j)
    l[j] = (pose.to_base(geometry_.platform_joints_mm[j]) - geometry_.base_joints_mm[j]).norm();
  return l;
}

Eigen::Vector3d Tripod::plane_residuals_mm(const Pose& pose) const noexcept {
  Eigen::Vector3d g;
  for (int j = 0; j < 3; ++j) {
    g[j] = geometry_.base_axes[j].dot(pose.to_base(geometry_.platform_joints_mm[j]) -
                                      geometry_.base_joints_mm[j]);
  }
  return g;
}

Result<ActuatorVector> Tripod::inverse(const Pose& pose) const {
  auto complete = complete_pose(pose);
  if (!complete) return complete.error();
  const Eigen::Vector3d l = strut_lengths(*complete);
  for (int j = 0; j < 3; ++j) {
    if (!(l[j] > 0.0)) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("strut {} would have zero length: platform joint on its base joint", j + 1));
    }
  }
  ActuatorVector out(3);
  out = l;
  return out;
}

bool Tripod::actuator_values(const Pose& pose, double* out) const noexcept {
  // As inverse(): the dependent coordinates completed (complete_pose), then the strut lengths.
  const PoseVector c = vector_from_pose(convention_, pose);
  TripodDependents d;
  if (!solve_dependents(tilt_of(c), yaw_branch_, d)) return false;
  const Eigen::Vector3d l = strut_lengths(pose_of(c, d));
  for (int j = 0; j < 3; ++j) {
    if (!(l[j] > 0.0)) return false;
    out[j] = l[j];
  }
  return true;
}

int Tripod::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  auto complete = complete_pose(pose);
  if (!complete) return -1;
  for (int j = 0; j < 3; ++j) {
    out.base_mm[j] = geometry_.base_joints_mm[j];
    out.platform_mm[j] = complete->to_base(geometry_.platform_joints_mm[j]);
  }
  out.platform_rotation = complete->rotation;
  out.mounts_turn = false;
  return 3;
}

bool Tripod::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  auto complete = complete_pose(pose);
  if (!complete) return false;
  StrutJointPoints joints;
  if (strut_joints(*complete, joints) != 3) return false;
  return strut_length_twist_jacobian(joints, 3, complete->position_mm, out);
}

namespace {

/// Twist rows (v, ω about the tool point) of the strut lengths (29) and of the plane constraints (31).
bool tripod_twist_rows(const TripodGeometry& geometry, const Pose& p,
                       Eigen::Matrix<double, 3, 6>& length_twist,
                       Eigen::Matrix<double, 3, 6>& plane_twist) noexcept {
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d arm = p.rotation * geometry.platform_joints_mm[j];
    const Eigen::Vector3d strut = arm + p.position_mm - geometry.base_joints_mm[j];
    const double length = strut.norm();
    if (!(length > 0.0)) return false;
    const Eigen::Vector3d unit = strut / length;
    length_twist.block<1, 3>(j, 0) = unit.transpose();
    length_twist.block<1, 3>(j, 3) = arm.cross(unit).transpose();
    plane_twist.block<1, 3>(j, 0) = geometry.base_axes[j].transpose();
    plane_twist.block<1, 3>(j, 3) = arm.cross(geometry.base_axes[j]).transpose();
  }
  return true;
}

}  // namespace

bool Tripod::dependent_rates(const Pose& p, Eigen::Matrix<double, 6, 6>& coordinate_twist,
                             Eigen::Matrix3d& dependent_per_controlled) const noexcept {
  Eigen::Matrix<double, 3, 6> length_twist, plane_twist;
  if (!tripod_twist_rows(geometry_, p, length_twist, plane_twist)) return false;
  coordinate_twist = coordinate_twists(convention_, p);
  const Eigen::Matrix<double, 3, 6> dg = plane_twist * coordinate_twist;
  // Implicit differentiation: g(q, d) = 0 ⇒ dd/dq = −(∂g/∂d)⁻¹ ∂g/∂q.
  const AxisMask mask = controlled_axes();
  Eigen::Matrix3d gq, gd;
  int nq = 0, nd = 0;
  for (int i = 0; i < 6; ++i) (mask.controlled[i] ? gq.col(nq++) : gd.col(nd++)) = dg.col(i);
  const Eigen::PartialPivLU<Eigen::Matrix3d> lu(gd);
  if (!(lu.rcond() > 1e-12)) return false;
  dependent_per_controlled = -lu.solve(gq);
  return true;
}

bool Tripod::controlled_twists(const Pose& pose, TwistBasis& out) const noexcept {
  auto complete = complete_pose(pose);
  if (!complete) return false;
  Eigen::Matrix<double, 6, 6> all;
  Eigen::Matrix3d dd_dq;
  if (!dependent_rates(*complete, all, dd_dq)) return false;
  const AxisMask mask = controlled_axes();
  Eigen::Matrix<double, 6, 3> tq, td;
  int nq = 0, nd = 0;
  for (int i = 0; i < 6; ++i) (mask.controlled[i] ? tq.col(nq++) : td.col(nd++)) = all.col(i);
  out.resize(6, 3);
  out = tq + td * dd_dq;
  return true;
}

Result<JacobianMatrix> Tripod::jacobian(const Pose& pose) const {
  auto complete = complete_pose(pose);
  if (!complete) return complete.error();
  Eigen::Matrix<double, 3, 6> length_twist, plane_twist;
  if (!tripod_twist_rows(geometry_, *complete, length_twist, plane_twist))
    return make_error(ErrorCode::singular, "a strut has zero length");
  Eigen::Matrix<double, 6, 6> all;
  Eigen::Matrix3d dd_dq;
  if (!dependent_rates(*complete, all, dd_dq)) {
    return make_error(
        ErrorCode::singular,
        "the revolute-plane constraints (31) are singular here: x, y and the yaw are not determined "
        "by z and the tilts (the two yaw branches meet)");
  }
  // dL/dq = ∂L/∂q + ∂L/∂d · dd/dq.
  const Eigen::Matrix<double, 3, 6> dl = length_twist * all;
  const AxisMask mask = controlled_axes();
  Eigen::Matrix3d lq, ld;
  int nq = 0, nd = 0;
  for (int i = 0; i < 6; ++i) (mask.controlled[i] ? lq.col(nq++) : ld.col(nd++)) = dl.col(i);
  JacobianMatrix out(3, 3);
  out = lq + ld * dd_dq;
  return out;
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Tripod::geometry_parameters() const {
  return {point_group("base_joints", "A", geometry_.base_joints_mm.data(), 3),
          point_group("platform_joints_from_tool", "B", geometry_.platform_joints_mm.data(), 3)};
}

Result<std::unique_ptr<Mechanism>> Tripod::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  TripodGeometry geometry = geometry_;
  for (int j = 0; j < 3; ++j) {
    geometry.base_joints_mm[j] = group_point(groups[0], j);
    geometry.platform_joints_mm[j] = group_point(groups[1], j);
  }
  auto tripod = Tripod::create(geometry, convention_, vector_from_pose(convention_, home_));
  if (!tripod) return tripod.error();
  return std::unique_ptr<Mechanism>(std::make_unique<Tripod>(std::move(tripod.value())));
}

}  // namespace pkm
