// All assembly modes of a tricept: the tool points whose three strut lengths are the given ones. The unknown
// is the tool point P alone (the central leg's cardan fixes the flange orientation from P, eqs. 34–36), so
// the modes are the solutions of three equations in three unknowns over the reachable half-space (P above
// the cardan point O, the leg extended). No reduction to one variable is known for this geometry; the modes
// are found by Newton from a fixed grid over that region (directions from O on a Fibonacci hemisphere ×
// radii up to the largest reach), every converged point kept once. The grid is dense against the size of
// the basins met on the shipped and random tricepts (tests/machine/tricept_all_modes_test.cpp checks that a
// grid four times denser finds nothing more).
#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"
#include "machine/solution_set.hpp"
#include "machine/tricept.hpp"

namespace pkm {

Result<AssemblyModes> Tricept::assembly_modes_on_grid(const ActuatorVector& q, int directions,
                                                      int radii) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("a tricept needs 3 strut lengths, got {}", q.size()));
  }
  for (int j = 0; j < 3; ++j) {
    if (!std::isfinite(q[j]) || !(q[j] > 0.0)) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("strut {} length {} is not a positive number", j + 1, q[j]));
    }
  }
  // The farthest a tool point can be from O: each flange joint within its strut's reach of its base joint.
  double reach_mm = 0.0;
  for (int j = 0; j < 3; ++j) {
    reach_mm = std::max(reach_mm, (geometry_.base_joints_mm[j] - geometry_.center_joint_mm).norm() + q[j] +
                                      geometry_.platform_joints_mm[j].norm());
  }
  reach_mm += std::abs(geometry_.tool_offset_mm);
  FkOptions options;
  options.require_same_branch = false;
  AssemblyModes modes;
  modes.report.method = fmt::format(
      "Newton from a grid of {} directions x {} radii over the reachable half-space", directions, radii);
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  for (int d = 0; d < directions; ++d) {
    // Fibonacci points on the upper hemisphere (z from 1 down to nearly 0).
    const double z = 1.0 - (d + 0.5) / directions;
    const double ring = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d direction(ring * std::cos(golden_angle * d), ring * std::sin(golden_angle * d), z);
    for (int r = 1; r <= radii; ++r) {
      Pose guess;
      guess.position_mm = geometry_.center_joint_mm + direction * (reach_mm * r / radii);
      auto solution = forward(q, guess, options);
      if (solution && !contains_solution(modes.solutions, solution->pose))
        modes.solutions.push_back(*solution);
    }
  }
  modes.report.real = static_cast<int>(modes.solutions.size());
  if (modes.solutions.empty()) {
    return make_error(ErrorCode::unreachable, "no tool point of the tricept fits these strut lengths");
  }
  sort_nearest_to(modes.solutions, home_, 100.0);
  return modes;
}

Result<AssemblyModes> Tricept::assembly_modes(const ActuatorVector& q, const FkOptions& /*options*/) const {
  return assembly_modes_on_grid(q, kAssemblyGridDirections, kAssemblyGridRadii);
}

Result<std::vector<FkSolution>> Tricept::forward_all(const ActuatorVector& q,
                                                     const FkOptions& options) const {
  auto modes = assembly_modes(q, options);
  if (!modes) return modes.error();
  return std::move(modes->solutions);
}

}  // namespace pkm
