// All assembly modes of a hexapod.
//
// Merged joints (6-3: platform joints pairwise merged; 3-6: base joints merged, solved for the inverse
// motion) use the dissertation's restructuring idea (§2.2.4): nine unknowns reduce to one. Each merged
// platform point P_k lies on the circle where the spheres of its two struts meet; fixing the angle θ of P_0
// on its circle fixes P_1 and P_2 up to two branches each (rigid distances |P_0P_1|, |P_0P_2|), and the
// remaining distance |P_1P_2| gives one scalar equation in θ. Scanning θ on each of the four branch pairs and
// bisecting every sign change finds every assembly mode.
//
// Every layout also goes through the parameter homotopy of kinematics/stewart_all_modes.hpp (40 paths), the
// only method for a general 6-6 layout. Each candidate is polished by the platform Newton solver to the
// usual strut residual, and labelled.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/units.hpp"
#include "kinematics/platform_newton.hpp"
#include "kinematics/root_scan.hpp"
#include "kinematics/stewart_all_modes.hpp"
#include "machine/hexapod.hpp"
#include "machine/solution_set.hpp"

namespace pkm {
namespace {

struct Circle {
  Eigen::Vector3d centre, u, v;
  double radius;
  Eigen::Vector3d at(double theta) const {
    return centre + radius * (std::cos(theta) * u + std::sin(theta) * v);
  }
};

std::optional<Circle> sphere_sphere(const Eigen::Vector3d& a, double ra, const Eigen::Vector3d& b,
                                    double rb) {
  const Eigen::Vector3d ab = b - a;
  const double d = ab.norm();
  if (d < 1e-12) return std::nullopt;
  const Eigen::Vector3d n = ab / d;
  const double x = (d * d + ra * ra - rb * rb) / (2 * d);
  const double h2 = ra * ra - x * x;
  if (h2 < 0) return std::nullopt;
  Circle c;
  c.centre = a + x * n;
  c.radius = std::sqrt(h2);
  c.u = n.unitOrthogonal();
  c.v = n.cross(c.u);
  return c;
}

// Point on `circle` at distance `distance` from `from`, branch ±1.
std::optional<Eigen::Vector3d> point_at_distance(const Circle& circle, const Eigen::Vector3d& from,
                                                 double distance, int branch) {
  const Eigen::Vector3d w = circle.centre - from;
  const double alpha = 2 * circle.radius * w.dot(circle.u);
  const double beta = 2 * circle.radius * w.dot(circle.v);
  const double gamma = distance * distance - w.squaredNorm() - circle.radius * circle.radius;
  const double amplitude = std::hypot(alpha, beta);
  if (amplitude < 1e-300 || std::abs(gamma) > amplitude) return std::nullopt;
  const double theta = std::atan2(beta, alpha) + branch * std::acos(gamma / amplitude);
  return circle.at(theta);
}

using JointSet = std::array<Eigen::Vector3d, 6>;
using StrutPairs = std::array<std::array<int, 2>, 3>;

// The struts whose joints in `points` coincide in pairs (three pairs), if they do.
std::optional<StrutPairs> merged_joint_pairs(const JointSet& points) {
  StrutPairs pairs{};
  std::array<bool, 6> used{};
  int count = 0;
  for (int j = 0; j < 6 && count < 3; ++j) {
    if (used[j]) continue;
    for (int k = j + 1; k < 6; ++k) {
      if (!used[k] && (points[j] - points[k]).norm() < 1e-9) {
        pairs[count++] = {j, k};
        used[j] = used[k] = true;
        break;
      }
    }
  }
  if (count < 3) return std::nullopt;
  return pairs;
}

// Candidate poses (unpolished) for |p + R·b_j − A_j| = q_j with the platform joints b merged in `pairs`.
Result<std::vector<Pose>> merged_platform_candidates(const JointSet& base, const JointSet& platform,
                                                     const ActuatorVector& q, const StrutPairs& pairs) {
  std::array<Circle, 3> circles;
  std::array<Eigen::Vector3d, 3> body;
  for (int k = 0; k < 3; ++k) {
    const auto [a, b] = pairs[k];
    auto c = sphere_sphere(base[a], q[a], base[b], q[b]);
    if (!c) {
      return make_error(ErrorCode::unreachable,
                        fmt::format("struts {} and {} cannot meet: lengths {:.6f} and {:.6f} mm", a + 1,
                                    b + 1, q[a], q[b]));
    }
    circles[k] = *c;
    body[k] = platform[a];
  }
  const double d01 = (body[1] - body[0]).norm();
  const double d02 = (body[2] - body[0]).norm();
  const double d12 = (body[2] - body[1]).norm();

  auto residual = [&](double theta, int b1, int b2,
                      std::array<Eigen::Vector3d, 3>& points) -> std::optional<double> {
    points[0] = circles[0].at(theta);
    auto p1 = point_at_distance(circles[1], points[0], d01, b1);
    auto p2 = point_at_distance(circles[2], points[0], d02, b2);
    if (!p1 || !p2) return std::nullopt;
    points[1] = *p1;
    points[2] = *p2;
    return (points[2] - points[1]).squaredNorm() - d12 * d12;
  };

  std::vector<Pose> candidates;
  constexpr int kSamples = 2880;
  for (int b1 : {-1, 1}) {
    for (int b2 : {-1, 1}) {
      std::array<Eigen::Vector3d, 3> pts;
      auto branch_residual = [&](double theta) { return residual(theta, b1, b2, pts); };
      scan_roots(branch_residual, 0.0, 2 * kPi, kSamples, [&](double) {
        // The platform pose that puts its three merged joints at these points.
        Eigen::Matrix3d from, to;
        for (int k = 0; k < 3; ++k) {
          from.col(k) = body[k];
          to.col(k) = pts[k];
        }
        const Eigen::Matrix4d t = Eigen::umeyama(from, to, false);
        Pose guess;
        guess.rotation = t.topLeftCorner<3, 3>();
        guess.position_mm = t.topRightCorner<3, 1>();
        candidates.push_back(guess);
      });
    }
  }
  return candidates;
}

// The inverse motion: if the platform frame sits at `pose` in the base frame, the base frame sits at the
// returned pose in the platform frame (the roles of base and platform joints swap).
Pose inverse_motion(const Pose& pose) {
  Pose inverse;
  inverse.rotation = pose.rotation.transpose();
  inverse.position_mm = -(inverse.rotation * pose.position_mm);
  return inverse;
}

// Whether the layout is architecturally singular: det J = 0 at every pose (similar planar base and platform
// hexagons on a conic, Griffis–Duffy-like layouts), tested at a few unrelated poses. det J scales as the
// platform's size cubed.
bool architecturally_singular(const Hexapod& hexapod, const JointSet& platform) {
  double size_mm = 0.0;
  for (const Eigen::Vector3d& b : platform) size_mm = std::max(size_mm, b.norm());
  const std::array<Eigen::Vector3d, 3> axes = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-2, 1, 0.5),
                                               Eigen::Vector3d(0.3, -1, 2)};
  for (int k = 0; k < 3; ++k) {
    Pose pose;
    pose.rotation = Eigen::AngleAxisd(0.2 + 0.15 * k, axes[k].normalized()).toRotationMatrix();
    pose.position_mm = Eigen::Vector3d(0.1 * k, -0.07 * k, 1.0 + 0.2 * k) * std::max(size_mm, 1.0);
    if (std::abs(hexapod.twist_jacobian(pose).determinant()) > 1e-9 * std::pow(std::max(size_mm, 1.0), 3)) {
      return false;
    }
  }
  return true;
}

}  // namespace

Result<AssemblyModes> Hexapod::assembly_modes(const ActuatorVector& q, const FkOptions& options) const {
  if (q.size() != 6) return make_error(ErrorCode::bad_input, "a hexapod needs 6 strut lengths");
  for (int j = 0; j < 6; ++j) {
    if (!std::isfinite(q[j]) || !(q[j] > 0.0)) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("strut {} length {} is not a positive number", j + 1, q[j]));
    }
  }
  const JointSet& base = geometry_.base_joints_mm;
  const JointSet& platform = geometry_.platform_joints_mm;
  if (architecturally_singular(*this, platform)) {
    return make_error(
        ErrorCode::singular,
        "this hexapod layout is architecturally singular (det J = 0 at every pose: e.g. similar "
        "planar base and platform on a conic, Griffis-Duffy-like): strut lengths that fit one pose "
        "fit a continuum of them, so there are no isolated assembly modes to list");
  }
  AssemblyModes modes;
  AssemblyModeReport& report = modes.report;
  std::vector<Pose> candidates;
  // Every layout goes through the homotopy; merged joints also through the 1-D scan, and the union is kept
  // (the scan can miss a pair of roots closer than one sample or at the edge of a branch: the tests found
  // such cases, which the homotopy did not miss).
  if (auto pairs = merged_joint_pairs(platform)) {
    report.method = "1-D scan of the merged platform joints (6-3 layout) and ";
    auto found = merged_platform_candidates(base, platform, q, *pairs);
    if (!found) return found.error();
    candidates = std::move(*found);
  } else if (auto base_pairs = merged_joint_pairs(base)) {
    // 3-6: the inverse motion is a 6-3 hexapod with the base joints on its platform.
    report.method = "1-D scan of the merged base joints (3-6 layout, the inverse motion) and ";
    auto found = merged_platform_candidates(platform, base, q, *base_pairs);
    if (!found) return found.error();
    for (const Pose& inverse : *found) candidates.push_back(inverse_motion(inverse));
  }
  std::array<double, 6> lengths_mm;
  for (int j = 0; j < 6; ++j) lengths_mm[j] = q[j];
  StewartAllModesOptions homotopy;
  homotopy.threads = options.threads;
  const StewartAllModes all = stewart_all_modes(base, platform, lengths_mm, homotopy);
  report.method += "parameter homotopy from a generic 6-6 instance (40 paths)";
  report.complex = all.complex;
  report.at_infinity = all.at_infinity;
  report.singular = all.singular;
  report.failed = all.failed;
  for (const StewartModeCandidate& mode : all.real) candidates.push_back(mode.pose);
  FkOptions polish = options;
  polish.require_same_branch = false;
  int unpolished_singular = 0;
  for (const Pose& guess : candidates) {
    auto polished = solve_platform_fk(*this, true, q, guess, polish);
    if (polished && !contains_solution(modes.solutions, polished->pose)) {
      const int mode = assembly_mode(polished->pose);
      polished->branch = mode == home_mode_ ? 0 : mode + 1;
      modes.solutions.push_back(*polished);
    } else if (!polished && polished.error().code == ErrorCode::singular) {
      ++unpolished_singular;  // a real solution where modes meet: Newton cannot polish it to the tolerance
    }
  }
  report.real = static_cast<int>(modes.solutions.size());
  // The scan and the homotopy may both have seen the same singular solution: count the larger of the two.
  report.singular = std::max(report.singular, unpolished_singular);
  if (modes.solutions.empty() && unpolished_singular > 0) {
    return make_error(ErrorCode::singular,
                      "these strut lengths fit only singular assemblies of the platform (where two assembly "
                      "modes meet): none can be polished to an isolated mode");
  }
  if (modes.solutions.empty()) {
    return make_error(ErrorCode::unreachable, "no assembly of the platform fits these strut lengths");
  }
  // Nearest to home first, so the first solution is the one a warm-started solver would give.
  sort_nearest_to(modes.solutions, home_, 100.0);
  return modes;
}

Result<std::vector<FkSolution>> Hexapod::forward_all(const ActuatorVector& q,
                                                     const FkOptions& options) const {
  auto modes = assembly_modes(q, options);
  if (!modes) return modes.error();
  return std::move(modes->solutions);
}

}  // namespace pkm
