// All assembly modes of a 6-3 hexapod by the dissertation's restructuring idea (ch2 §4.6(d)): nine unknowns
// reduce to one. Each merged platform point P_k lies on the circle where the spheres of its two struts meet;
// fixing the angle θ of P_0 on its circle fixes P_1 and P_2 up to two branches each (rigid distances
// |P_0P_1|, |P_0P_2|), and the remaining distance |P_1P_2| gives one scalar equation in θ. Scanning θ on each
// of the four branch pairs and bisecting every sign change finds every assembly mode; each is polished by
// Newton.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <optional>

#include "core/units.hpp"
#include "kinematics/platform_newton.hpp"
#include "kinematics/root_scan.hpp"
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

}  // namespace

Result<std::vector<FkSolution>> Hexapod::forward_all(const ActuatorVector& q,
                                                     const FkOptions& options) const {
  if (!six_three_) {
    return make_error(
        ErrorCode::unsupported,
        "enumerating every assembly mode needs a 6-3 hexapod (platform joints merged in pairs); for a 6-6 "
        "layout solve from a guess");
  }
  if (q.size() != 6) return make_error(ErrorCode::bad_input, "a hexapod needs 6 strut lengths");
  // Group struts by their shared platform point.
  std::array<std::array<int, 2>, 3> pairs{};
  std::array<bool, 6> used{};
  int count = 0;
  for (int j = 0; j < 6 && count < 3; ++j) {
    if (used[j]) continue;
    for (int k = j + 1; k < 6; ++k) {
      if (!used[k] && (geometry_.platform_joints_mm[j] - geometry_.platform_joints_mm[k]).norm() < 1e-9) {
        pairs[count++] = {j, k};
        used[j] = used[k] = true;
        break;
      }
    }
  }
  std::array<Circle, 3> circles;
  std::array<Eigen::Vector3d, 3> body;
  for (int k = 0; k < 3; ++k) {
    const auto [a, b] = pairs[k];
    auto c = sphere_sphere(geometry_.base_joints_mm[a], q[a], geometry_.base_joints_mm[b], q[b]);
    if (!c) {
      return make_error(ErrorCode::unreachable,
                        fmt::format("struts {} and {} cannot meet: lengths {:.6f} and {:.6f} mm", a + 1,
                                    b + 1, q[a], q[b]));
    }
    circles[k] = *c;
    body[k] = geometry_.platform_joints_mm[a];
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

  std::vector<FkSolution> solutions;
  constexpr int kSamples = 2880;
  FkOptions polish = options;
  polish.require_same_branch = false;
  for (int b1 : {-1, 1}) {
    for (int b2 : {-1, 1}) {
      std::array<Eigen::Vector3d, 3> pts;
      auto branch_residual = [&](double theta) { return residual(theta, b1, b2, pts); };
      scan_roots(branch_residual, 0.0, 2 * kPi, kSamples, [&](double) {
        // The platform pose that puts its three merged joints at these points, then Newton's polish.
        Eigen::Matrix3d from, to;
        for (int k = 0; k < 3; ++k) {
          from.col(k) = body[k];
          to.col(k) = pts[k];
        }
        const Eigen::Matrix4d t = Eigen::umeyama(from, to, false);
        Pose guess;
        guess.rotation = t.topLeftCorner<3, 3>();
        guess.position_mm = t.topRightCorner<3, 1>();
        auto polished = solve_platform_fk(*this, true, q, guess, polish);
        if (polished && !contains_solution(solutions, polished->pose)) {
          const int mode = assembly_mode(polished->pose);
          polished->branch = mode == home_mode_ ? 0 : mode + 1;
          solutions.push_back(*polished);
        }
      });
    }
  }
  if (solutions.empty()) {
    return make_error(ErrorCode::unreachable, "no assembly of the platform fits these strut lengths");
  }
  // Nearest to home first, so the first solution is the one a warm-started solver would give.
  sort_nearest_to(solutions, home_, 100.0);
  return solutions;
}

}  // namespace pkm
