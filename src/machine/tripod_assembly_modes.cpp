// All assembly modes of the 3-RPS tripod by a one-dimensional reduction of the joint-angle system of ch2
// §4.13. Each platform joint B_j moves on a circle (radius L_j about A_j, in the plane of strut j). Fixing
// the joint angle t_1 fixes B_1; the rigid distances |B_1B_2| and |B_1B_3| then give t_2 and t_3 in closed
// form, two branches each (α cos t + β sin t = γ), and the remaining distance |B_2B_3| leaves one scalar
// equation in t_1. Scanning t_1 on each of the four branch pairs and bisecting every sign change finds the
// assembly modes; each is polished by the Newton solver of `forward`. Roots closer together than the scan
// step, or at the very end of a branch (where its arc ends), can be missed; duplicates are removed.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/units.hpp"
#include "kinematics/root_scan.hpp"
#include "machine/solution_set.hpp"
#include "machine/tripod.hpp"

namespace pkm {

Result<std::vector<FkSolution>> Tripod::forward_all(const ActuatorVector& q, const FkOptions& options) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("a tripod needs 3 strut lengths, got {}", q.size()));
  }
  const Eigen::Vector3d l = q.head<3>();
  for (int j = 0; j < 3; ++j) {
    if (!(l[j] > 0.0))
      return make_error(ErrorCode::bad_input, fmt::format("strut {} length must be positive", j + 1));
  }
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();

  // Joint angle of strut k whose joint lies at `distance` from `from`, branch ±1.
  auto angle_at_distance = [&](int k, const Eigen::Vector3d& from, double distance,
                               int branch) -> std::optional<double> {
    const Eigen::Vector3d d = geometry_.base_joints_mm[k] - from;
    const Eigen::Vector3d side = geometry_.base_axes[k].cross(up);
    const double alpha = d.dot(up), beta = d.dot(side);
    const double gamma = (distance * distance - d.squaredNorm() - l[k] * l[k]) / (2.0 * l[k]);
    const double amplitude = std::hypot(alpha, beta);
    if (!(amplitude > 1e-300) || std::abs(gamma) > amplitude) return std::nullopt;
    return std::atan2(beta, alpha) + branch * std::acos(gamma / amplitude);
  };
  const double d12 = platform_distance_mm_[0], d23 = platform_distance_mm_[1], d31 = platform_distance_mm_[2];
  auto residual = [&](double t1, int b2, int b3,
                      std::array<Eigen::Vector3d, 3>& joints) -> std::optional<double> {
    joints[0] = joint_at(0, l[0], t1);
    const auto t2 = angle_at_distance(1, joints[0], d12, b2);
    const auto t3 = angle_at_distance(2, joints[0], d31, b3);
    if (!t2 || !t3) return std::nullopt;
    joints[1] = joint_at(1, l[1], *t2);
    joints[2] = joint_at(2, l[2], *t3);
    return (joints[2] - joints[1]).squaredNorm() - d23 * d23;
  };

  std::vector<FkSolution> solutions;
  constexpr int kTripodScanSamples = 2880;
  FkOptions polish = options;
  polish.require_same_branch = false;
  for (int b2 : {-1, 1}) {
    for (int b3 : {-1, 1}) {
      std::array<Eigen::Vector3d, 3> joints;
      auto branch_residual = [&](double t1) { return residual(t1, b2, b3, joints); };
      scan_roots(branch_residual, -kPi, kPi, kTripodScanSamples, [&](double) {
        auto polished = forward(q, pose_from_joints(joints), polish);
        if (polished && !contains_solution(solutions, polished->pose)) solutions.push_back(*polished);
      });
    }
  }
  if (solutions.empty()) {
    return make_error(ErrorCode::unreachable, "no assembly of the tripod platform fits these strut lengths");
  }
  // Nearest to home first, so the first solution is the one a warm-started solver would give.
  sort_nearest_to(solutions, home_, 100.0);
  return solutions;
}

}  // namespace pkm
