#include "machine/rotopod.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "core/units.hpp"
#include "kinematics/coordinate_jacobian.hpp"
#include "kinematics/platform_newton.hpp"

namespace pkm {
namespace {

// The closed form (pkm's own) about the nearest point of the circle.
struct CircleReach {
  double nearest_rad;  ///< φ_near
  double cosine;       ///< cos(φ − φ_near); |cosine| > 1: unreachable
  double radial_mm;    ///< ρ, horizontal distance of B from the circle's axis
  double height_mm;    ///< Δz = z_j − z_B
};

CircleReach circle_reach(const RotopodGeometry& g, int j, const Eigen::Vector3d& joint) {
  const Eigen::Vector2d e = joint.head<2>() - g.circle_center_mm;
  const double rho = e.norm();
  const double dz = g.joint_heights_mm[j] - joint.z();
  const double r = g.circle_radius_mm;
  const double length = g.strut_lengths_mm[j];
  return {std::atan2(e.y(), e.x()), (r * r + rho * rho + dz * dz - length * length) / (2.0 * r * rho), rho,
          dz};
}

// Angle in the 2π window centred on `centre_rad`.
double wrap_near(double angle_rad, double centre_rad) {
  return centre_rad + std::remainder(angle_rad - centre_rad, 2.0 * kPi);
}

// Legs for solve_platform_fk whose angles are reported near the target angles, so that residuals never jump
// by 2π.
struct TargetWindowLegs {
  const Rotopod& rotopod;
  const ActuatorVector& target;
  int leg_count() const { return 6; }
  const Eigen::Vector3d& platform_joint(int j) const { return rotopod.geometry().platform_joints_mm[j]; }
  bool leg_value(int j, const Eigen::Vector3d& joint, double& q, Eigen::Vector3d& g) const {
    return rotopod.carriage_angle(j, joint, target[j], q, g);
  }
};

}  // namespace

Rotopod::Rotopod(const RotopodGeometry& geometry, AngleConvention convention, const Pose& home)
    : geometry_(geometry), convention_(convention) {
  home_ = home;
  auto home_angles = angles(home_, reference_rad_);  // window (−π, π] around the zero references
  if (home_angles) {
    for (int j = 0; j < 6; ++j) reference_rad_[j] = (*home_angles)[j];
  }
  home_mode_ = assembly_mode(home_);
}

Eigen::Vector3d Rotopod::carriage_mm(int j, double angle_rad) const {
  const double r = geometry_.circle_radius_mm;
  return {geometry_.circle_center_mm.x() + r * std::cos(angle_rad),
          geometry_.circle_center_mm.y() + r * std::sin(angle_rad), geometry_.joint_heights_mm[j]};
}

void Rotopod::base_joint_motion(int /*strut*/, double actuator, Eigen::Vector3d& first,
                                Eigen::Vector3d& second) const noexcept {
  const double r = geometry_.circle_radius_mm;
  first = Eigen::Vector3d(-r * std::sin(actuator), r * std::cos(actuator), 0.0);
  second = Eigen::Vector3d(-r * std::cos(actuator), -r * std::sin(actuator), 0.0);
}

bool Rotopod::carriage_angle(int j, const Eigen::Vector3d& joint, double centre_rad, double& angle_rad,
                             Eigen::Vector3d& d_angle_dB) const {
  const CircleReach reach = circle_reach(geometry_, j, joint);
  if (!(std::abs(reach.cosine) < 1.0)) return false;  // also rejects ρ = 0 (NaN or ±∞)
  angle_rad = wrap_near(reach.nearest_rad + geometry_.branches[j] * std::acos(reach.cosine), centre_rad);
  const Eigen::Vector3d strut = carriage_mm(j, angle_rad) - joint;  // A − B
  const Eigen::Vector3d tangent(-std::sin(angle_rad), std::cos(angle_rad), 0.0);
  const double denominator = geometry_.circle_radius_mm * strut.dot(tangent);
  if (!(std::abs(denominator) > 0.0)) return false;
  d_angle_dB = strut / denominator;
  return true;
}

int Rotopod::carriage_angles(const Pose& pose, const std::array<double, 6>& centres_rad,
                             double* out) const noexcept {
  for (int j = 0; j < 6; ++j) {
    const CircleReach reach = circle_reach(geometry_, j, pose.to_base(geometry_.platform_joints_mm[j]));
    if (!(reach.radial_mm > 0.0) || !(std::abs(reach.cosine) <= 1.0)) return j;
    out[j] = wrap_near(reach.nearest_rad + geometry_.branches[j] * std::acos(reach.cosine), centres_rad[j]);
  }
  return -1;
}

Result<ActuatorVector> Rotopod::angles(const Pose& pose, const std::array<double, 6>& centres_rad) const {
  ActuatorVector phi(6);
  const int j = carriage_angles(pose, centres_rad, phi.data());
  if (j < 0) return phi;
  const CircleReach reach = circle_reach(geometry_, j, pose.to_base(geometry_.platform_joints_mm[j]));
  const double length = geometry_.strut_lengths_mm[j];
  if (!(reach.radial_mm > 0.0)) {
    return make_error(
        ErrorCode::singular,
        fmt::format("carriage {}: platform joint {} is on the circle's axis, where every carriage "
                    "angle (or none) fits",
                    j + 1, j + 1));
  }
  const double r = geometry_.circle_radius_mm;
  const double nearest = std::hypot(reach.radial_mm - r, reach.height_mm);
  const double farthest = std::hypot(reach.radial_mm + r, reach.height_mm);
  const bool too_short = length < nearest;
  return make_error(
      ErrorCode::unreachable,
      fmt::format("carriage {}: its {:.3f} mm strut cannot reach the carriage circle: {:.3f} mm "
                  "too {} (platform joint {:.3f} to {:.3f} mm from the circle)",
                  j + 1, length, too_short ? nearest - length : length - farthest,
                  too_short ? "short" : "long", nearest, farthest));
}

bool Rotopod::actuator_values(const Pose& pose, double* out) const noexcept {
  return carriage_angles(pose, reference_rad_, out) < 0;
}

Result<ActuatorVector> Rotopod::inverse(const Pose& pose) const {
  return angles(pose, reference_rad_);
}

int Rotopod::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d b = pose.to_base(geometry_.platform_joints_mm[j]);
    const CircleReach reach = circle_reach(geometry_, j, b);
    if (!(reach.radial_mm > 0.0) || !(std::abs(reach.cosine) <= 1.0)) return -1;
    const double angle = reach.nearest_rad + geometry_.branches[j] * std::acos(reach.cosine);
    out.base_mm[j] = carriage_mm(j, angle);
    out.platform_mm[j] = b;
    out.mount_yaw_rad[j] = angle;  // a carriage on the circle turns with its angle
  }
  out.platform_rotation = pose.rotation;
  out.mounts_turn = true;
  return 6;
}

bool Rotopod::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  return joint_gradient_twist_jacobian(
      pose, 6, geometry_.platform_joints_mm,
      [this](int j, const Eigen::Vector3d& joint_mm, Eigen::Vector3d& g) {
        double phi = 0.0;
        return carriage_angle(j, joint_mm, reference_rad_[j], phi, g);
      },
      out);
}

Result<JacobianMatrix> Rotopod::jacobian(const Pose& pose) const {
  JacobianMatrix twist(6, 6);
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d arm = pose.rotation * geometry_.platform_joints_mm[j];
    double phi = 0.0;
    Eigen::Vector3d g;
    if (!carriage_angle(j, arm + pose.position_mm, reference_rad_[j], phi, g)) {
      auto reachable = inverse(pose);
      if (!reachable) return reachable.error();
      return make_error(
          ErrorCode::singular,
          fmt::format("carriage {}: strut {} is perpendicular to the carriage's circle (inverse "
                      "singularity)",
                      j + 1, j + 1));
    }
    twist.block<1, 3>(j, 0) = g.transpose();
    twist.block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
  return coordinate_jacobian(twist, convention_, angles_from_rotation(convention_, pose.rotation),
                             AxisMask::all());
}

double Rotopod::strut_line_determinant(const Pose& pose) const {
  auto phi = inverse(pose);
  if (!phi) return 0.0;
  Eigen::Matrix<double, 6, 6> lines;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d arm = pose.rotation * geometry_.platform_joints_mm[j];
    const Eigen::Vector3d n =
        (arm + pose.position_mm - carriage_mm(j, (*phi)[j])) / geometry_.strut_lengths_mm[j];
    lines.block<1, 3>(j, 0) = n.transpose();
    lines.block<1, 3>(j, 3) = arm.cross(n).transpose();
  }
  return lines.determinant();
}

double Rotopod::path_conditioning(const Pose& pose) const {
  auto phi = inverse(pose);
  if (!phi) return 0.0;
  double worst = 1.0;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d strut = carriage_mm(j, (*phi)[j]) - pose.to_base(geometry_.platform_joints_mm[j]);
    const Eigen::Vector3d tangent(-std::sin((*phi)[j]), std::cos((*phi)[j]), 0.0);
    worst = std::fmin(worst, std::abs(strut.dot(tangent)) / geometry_.strut_lengths_mm[j]);
  }
  return worst;
}

int Rotopod::assembly_mode(const Pose& pose) const {
  const double det = strut_line_determinant(pose);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

Result<FkSolution> Rotopod::forward(const ActuatorVector& actuators, const Pose& guess,
                                    const FkOptions& options) const {
  if (actuators.size() != 6) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("a rotopod needs 6 carriage angles, got {}", actuators.size()));
  }
  const TargetWindowLegs legs{*this, actuators};
  auto solution = solve_platform_fk(legs, true, actuators, guess, options);
  if (!solution) return solution;
  const int mode = assembly_mode(solution->pose);
  solution->branch = mode == home_mode_ ? 0 : 1;
  // A guess at a singular or unreachable pose has no mode to keep.
  const int guess_mode = options.require_same_branch ? assembly_mode(guess) : 0;
  if (guess_mode != 0 && mode != guess_mode) {
    return another_assembly_mode_error(solution->pose);
  }
  return solution;
}

Pose rotopod_default_home(const RotopodGeometry& geometry) {
  // Argument 0 of the arccos: Δz_j² = L_j² − R² − ρ_j², with ρ_j = |b'_j,xy| when the tool is over the
  // centre.
  const double r = geometry.circle_radius_mm;
  double z = 0.0;
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d& b = geometry.platform_joints_mm[j];
    const double length = geometry.strut_lengths_mm[j];
    const double rise = std::sqrt(std::fmax(length * length - r * r - b.head<2>().squaredNorm(), 0.0));
    z += (geometry.joint_heights_mm[j] + rise - b.z()) / 6.0;
  }
  Pose home;
  home.position_mm << geometry.circle_center_mm.x(), geometry.circle_center_mm.y(), z;
  return home;
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Rotopod::geometry_parameters() const {
  const Eigen::Vector2d& o = geometry_.circle_center_mm;
  GeometryGroup center{"circle_center", "O", {"x", "y"}, "mm", 1, {o.x(), o.y()}};
  GeometryGroup radius{"circle_radius", "R", {""}, "mm", 1, {geometry_.circle_radius_mm}};
  GeometryGroup heights{"joint_heights",
                        "z",
                        {""},
                        "mm",
                        6,
                        {geometry_.joint_heights_mm.begin(), geometry_.joint_heights_mm.end()}};
  GeometryGroup lengths{"strut_lengths",
                        "L",
                        {""},
                        "mm",
                        6,
                        {geometry_.strut_lengths_mm.begin(), geometry_.strut_lengths_mm.end()}};
  return {std::move(center), std::move(radius), std::move(heights), std::move(lengths),
          point_group("platform_joints_from_tool", "B", geometry_.platform_joints_mm.data(), 6)};
}

Result<std::unique_ptr<Mechanism>> Rotopod::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  RotopodGeometry geometry = geometry_;  // branches are kept
  geometry.circle_center_mm = Eigen::Vector2d(groups[0].values[0], groups[0].values[1]);
  geometry.circle_radius_mm = groups[1].values[0];
  if (!(geometry.circle_radius_mm > 0.0))
    return make_error(ErrorCode::bad_input, "the circle radius must be positive");
  for (int j = 0; j < 6; ++j) {
    const auto row = static_cast<std::size_t>(j);
    geometry.joint_heights_mm[row] = groups[2].values[row];
    geometry.strut_lengths_mm[row] = groups[3].values[row];
    geometry.platform_joints_mm[row] = group_point(groups[4], j);
    if (!(geometry.strut_lengths_mm[row] > 0.0)) {
      return make_error(ErrorCode::bad_input, fmt::format("strut length L{} must be positive", j + 1));
    }
  }
  return std::unique_ptr<Mechanism>(std::make_unique<Rotopod>(geometry, convention_, home_));
}

}  // namespace pkm
