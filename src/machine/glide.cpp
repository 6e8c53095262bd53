#include "machine/glide.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "kinematics/coordinate_jacobian.hpp"
#include "kinematics/platform_newton.hpp"

namespace pkm {
namespace {

// Sphere (centre B, radius l) against the line P + s·e, with w = B − P: the roots are s = along ±
// √discriminant.
struct SphereLine {
  double along_mm;          ///< e·w, the foot of the perpendicular from B
  double discriminant_mm2;  ///< l² − h², h the distance of B from the line
  double distance_mm;       ///< h
};

SphereLine sphere_line(const Eigen::Vector3d& w, const Eigen::Vector3d& e, double length_mm) {
  const double along = e.dot(w);
  const double h2 = (w - along * e).squaredNorm();
  return {along, length_mm * length_mm - h2, std::sqrt(h2)};
}

using StrutLines = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

}  // namespace

Glide::Glide(const GlideGeometry& geometry, AngleConvention convention, const Pose& home)
    : geometry_(geometry), convention_(convention) {
  for (int j = 0; j < geometry_.count; ++j) geometry_.guide_directions[j].normalize();
  home_ = fixed_orientation(home);
  home_mode_ = assembly_mode(home_);
}

Pose Glide::fixed_orientation(const Pose& pose) const {
  if (rotates()) return pose;
  Pose out = pose;
  out.rotation.setIdentity();
  return out;
}

Result<Pose> Glide::complete_pose(const Pose& pose) const {
  return fixed_orientation(pose);
}

bool Glide::leg_value(int j, const Eigen::Vector3d& joint, double& q, Eigen::Vector3d& g) const {
  const Eigen::Vector3d& e = geometry_.guide_directions[j];
  const SphereLine x = sphere_line(joint - geometry_.guide_points_mm[j], e, geometry_.strut_lengths_mm[j]);
  if (!(x.discriminant_mm2 > 0.0)) return false;
  const double root = std::sqrt(x.discriminant_mm2);
  const double sigma = geometry_.branches[j];
  q = x.along_mm + sigma * root;
  // ∂s/∂B = (B − C)/((B − C)·e) with (B − C)·e = e·w − s = −σ√D.
  g = (joint - carriage_mm(j, q)) / (-sigma * root);
  return true;
}

int Glide::carriage_positions(const Pose& pose, double* out) const noexcept {
  const Pose p = fixed_orientation(pose);
  for (int j = 0; j < geometry_.count; ++j) {
    const Eigen::Vector3d b = p.to_base(geometry_.platform_joints_mm[j]);
    const SphereLine x = sphere_line(b - geometry_.guide_points_mm[j], geometry_.guide_directions[j],
                                     geometry_.strut_lengths_mm[j]);
    if (!(x.discriminant_mm2 >= 0.0)) return j;  // also a NaN pose
    out[j] = x.along_mm + geometry_.branches[j] * std::sqrt(x.discriminant_mm2);
  }
  return -1;
}

Result<ActuatorVector> Glide::inverse(const Pose& pose) const {
  ActuatorVector s(geometry_.count);
  const int j = carriage_positions(pose, s.data());
  if (j < 0) return s;
  const Eigen::Vector3d b = fixed_orientation(pose).to_base(geometry_.platform_joints_mm[j]);
  const double length = geometry_.strut_lengths_mm[j];
  const SphereLine x = sphere_line(b - geometry_.guide_points_mm[j], geometry_.guide_directions[j], length);
  return make_error(
      ErrorCode::unreachable,
      fmt::format("carriage {}: its {:.3f} mm strut cannot reach guide {}: the platform joint is "
                  "{:.3f} mm from the guide line, {:.3f} mm too far",
                  j + 1, length, j + 1, x.distance_mm, x.distance_mm - length));
}

bool Glide::actuator_values(const Pose& pose, double* out) const noexcept {
  return carriage_positions(pose, out) < 0;
}

int Glide::strut_joints(const Pose& pose, StrutJointPoints& out) const {
  const Pose p = fixed_orientation(pose);
  for (int j = 0; j < geometry_.count; ++j) {
    const Eigen::Vector3d b = p.to_base(geometry_.platform_joints_mm[j]);
    const SphereLine x = sphere_line(b - geometry_.guide_points_mm[j], geometry_.guide_directions[j],
                                     geometry_.strut_lengths_mm[j]);
    if (x.discriminant_mm2 < 0.0) return -1;
    out.base_mm[j] = carriage_mm(j, x.along_mm + geometry_.branches[j] * std::sqrt(x.discriminant_mm2));
    out.platform_mm[j] = b;
  }
  out.platform_rotation = p.rotation;
  out.mounts_turn = false;  // carriages slide along straight guides without turning
  return geometry_.count;
}

bool Glide::twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept {
  return joint_gradient_twist_jacobian(
      fixed_orientation(pose), geometry_.count, geometry_.platform_joints_mm,
      [this](int j, const Eigen::Vector3d& joint_mm, Eigen::Vector3d& g) {
        double s = 0.0;
        return leg_value(j, joint_mm, s, g);
      },
      out);
}

MechanismStructure Glide::structure() const {
  if (rotates()) return {"6-PUS (hexaglide)", false, 14, {6, 6, 6, 0, 0}, 0};
  // Triglide: each carriage drives a parallelogram of two S–S struts; each strut can spin idly about its
  // axis.
  return {"3-P(2S-2S) (triglide)", false, 1 + 3 + 6 + 1, {3, 0, 12, 0, 0}, 6};
}

Result<JacobianMatrix> Glide::jacobian(const Pose& pose) const {
  const Pose p = fixed_orientation(pose);
  JacobianMatrix twist(geometry_.count, 6);
  for (int j = 0; j < geometry_.count; ++j) {
    const Eigen::Vector3d arm = p.rotation * geometry_.platform_joints_mm[j];
    double s = 0.0;
    Eigen::Vector3d g;
    if (!leg_value(j, arm + p.position_mm, s, g)) {
      auto reachable = inverse(p);
      if (!reachable) return reachable.error();
      return make_error(
          ErrorCode::singular,
          fmt::format("carriage {}: strut {} is perpendicular to its guide (inverse singularity)", j + 1,
                      j + 1));
    }
    twist.block<1, 3>(j, 0) = g.transpose();
    twist.block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
  return coordinate_jacobian(twist, convention_, angles_from_rotation(convention_, p.rotation),
                             controlled_axes());
}

double Glide::strut_line_determinant(const Pose& pose) const {
  const Pose p = fixed_orientation(pose);
  auto s = inverse(p);
  if (!s) return 0.0;
  StrutLines lines(geometry_.count, rotates() ? 6 : 3);
  for (int j = 0; j < geometry_.count; ++j) {
    const Eigen::Vector3d arm = p.rotation * geometry_.platform_joints_mm[j];
    const Eigen::Vector3d n = (arm + p.position_mm - carriage_mm(j, (*s)[j])) / geometry_.strut_lengths_mm[j];
    lines.block<1, 3>(j, 0) = n.transpose();
    if (rotates()) lines.block<1, 3>(j, 3) = arm.cross(n).transpose();
  }
  return lines.determinant();
}

int Glide::assembly_mode(const Pose& pose) const {
  const double det = strut_line_determinant(pose);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

double Glide::guide_conditioning(const Pose& pose) const {
  const Pose p = fixed_orientation(pose);
  double worst = 1.0;
  for (int j = 0; j < geometry_.count; ++j) {
    const double length = geometry_.strut_lengths_mm[j];
    const SphereLine x =
        sphere_line(p.to_base(geometry_.platform_joints_mm[j]) - geometry_.guide_points_mm[j],
                    geometry_.guide_directions[j], length);
    if (x.discriminant_mm2 < 0.0) return 0.0;
    worst = std::fmin(worst, std::sqrt(x.discriminant_mm2) / length);
  }
  return worst;
}

double Glide::angle_deviation_from_45(const Pose& pose) const {
  const Pose p = fixed_orientation(pose);
  const double half = std::sqrt(0.5);
  double worst = 0.0;
  for (int j = 0; j < geometry_.count; ++j) {
    const double length = geometry_.strut_lengths_mm[j];
    const SphereLine x =
        sphere_line(p.to_base(geometry_.platform_joints_mm[j]) - geometry_.guide_points_mm[j],
                    geometry_.guide_directions[j], length);
    if (x.discriminant_mm2 < 0.0) return std::numeric_limits<double>::infinity();
    worst = std::fmax(worst, std::abs(std::sqrt(x.discriminant_mm2) / length - half));
  }
  return worst;
}

Result<FkSolution> Glide::forward(const ActuatorVector& actuators, const Pose& guess,
                                  const FkOptions& options) const {
  if (actuators.size() != geometry_.count) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("this glide machine has {} carriages, got {} positions", geometry_.count,
                                  actuators.size()));
  }
  auto solution = solve_platform_fk(*this, rotates(), actuators, fixed_orientation(guess), options);
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

Result<Pose> glide_default_home(const GlideGeometry& geometry, AngleConvention convention) {
  const Glide probe(geometry, convention, Pose{});
  const int n = geometry.count;
  Eigen::Vector3d guide_centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_centroid = Eigen::Vector3d::Zero();
  double longest = 0.0;
  for (int j = 0; j < n; ++j) {
    guide_centroid += geometry.guide_points_mm[j] / static_cast<double>(n);
    joint_centroid += geometry.platform_joints_mm[j] / static_cast<double>(n);
    longest = std::fmax(longest, geometry.strut_lengths_mm[j]);
  }
  // The level platform with its joint centroid at height h over the guide-point centroid.
  auto pose_at = [&](double h) {
    Pose pose;
    pose.position_mm = guide_centroid - joint_centroid;
    pose.position_mm.z() += h;
    return pose;
  };
  // Objective 1: the worst deviation of the strut-to-guide angles from 45° (to minimise), halfway between the
  // inverse singularity (90°) and a strut along its guide (0°, where a level platform loses its stiffness
  // across the guides). Objective 2, for guides parallel to z where the angles do not depend on h: max_j
  // |s_j| (to minimise).
  auto deviation = [&](double h) { return probe.angle_deviation_from_45(pose_at(h)); };
  auto spread = [&](double h) {
    auto s = probe.inverse(pose_at(h));
    return s ? s->cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
  };
  constexpr int kScanSteps = 400;
  constexpr double kFlat = 1e-9;
  constexpr double kTie = 1e-12;  // mirror heights differ only by rounding
  const double step = 4.0 * longest / kScanSteps;
  double best_h = 0.0;
  double best_deviation = std::numeric_limits<double>::infinity();
  double worst_deviation = 0.0;
  for (int k = 0; k <= kScanSteps; ++k) {
    const double h = -2.0 * longest + k * step;  // lower heights win ties
    const double d = deviation(h);
    if (!std::isfinite(d)) continue;
    worst_deviation = std::fmax(worst_deviation, d);
    if (d < best_deviation - kTie) {
      best_deviation = d;
      best_h = h;
    }
  }
  if (!std::isfinite(best_deviation)) {
    return make_error(ErrorCode::unreachable,
                      "no platform height over the guide points lets every strut reach its guide");
  }
  const bool flat = worst_deviation - best_deviation <= kFlat;
  if (flat) {
    double best_spread = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= kScanSteps; ++k) {
      const double h = -2.0 * longest + k * step;
      const double sp = spread(h);
      if (sp < best_spread - kTie) {
        best_spread = sp;
        best_h = h;
      }
    }
  }
  // Golden-section refinement of the best cell.
  auto better = [&](double a, double b) {
    return flat ? spread(a) <= spread(b) : deviation(a) <= deviation(b);
  };
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = best_h - step, hi = best_h + step;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    if (better(a, b)) {
      hi = b;
    } else {
      lo = a;
    }
  }
  const double h = 0.5 * (lo + hi);
  return pose_at(better(h, best_h) ? h : best_h);
}

}  // namespace pkm

namespace pkm {

std::vector<GeometryGroup> Glide::geometry_parameters() const {
  const int n = geometry_.count;
  GeometryGroup lengths{"strut_lengths", "L", {""}, "mm", n, {}};
  lengths.values.assign(geometry_.strut_lengths_mm.begin(), geometry_.strut_lengths_mm.begin() + n);
  return {point_group("guide_points", "P", geometry_.guide_points_mm.data(), n), std::move(lengths),
          point_group("platform_joints_from_tool", "B", geometry_.platform_joints_mm.data(), n)};
}

Result<std::unique_ptr<Mechanism>> Glide::with_geometry(const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  GlideGeometry geometry = geometry_;  // count, guide directions and branches are kept
  for (int j = 0; j < geometry.count; ++j) {
    geometry.guide_points_mm[j] = group_point(groups[0], j);
    geometry.strut_lengths_mm[j] = groups[1].values[static_cast<std::size_t>(j)];
    geometry.platform_joints_mm[j] = group_point(groups[2], j);
    if (!(geometry.strut_lengths_mm[j] > 0.0)) {
      return make_error(ErrorCode::bad_input, fmt::format("strut length L{} must be positive", j + 1));
    }
  }
  return std::unique_ptr<Mechanism>(std::make_unique<Glide>(geometry, convention_, home_));
}

}  // namespace pkm
