#include "redundancy/trajectory_metrics.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace pkm::redundancy {

TrajectoryMetrics measure(const Problem& problem, const Trajectory& trajectory) {
  constexpr double kJoulePerNmm = 1e-3;
  const LawEvaluator& law = *problem.law;
  const int c = law.free().count();
  const int points = static_cast<int>(trajectory.nodes.size());
  TrajectoryMetrics metrics;
  metrics.max_increment_mm.assign(points, 0.0);
  metrics.max_force_N.assign(points, 0.0);
  metrics.cumulative_energy_J.assign(points, 0.0);
  metrics.min_rad = metrics.max_rad = trajectory.values.empty() ? FreeValues::Zero() : trajectory.values[0];
  const ActuatorLimits& limits = law.machine().limits;
  const bool ranged = limits.min && limits.max && *limits.max > *limits.min;
  metrics.min_limit_margin = ranged ? 0.5 : std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < points; ++k) {
    const Node& node = trajectory.nodes[k];
    for (int i = 0; i < c; ++i) {
      metrics.min_rad[i] = std::min(metrics.min_rad[i], trajectory.values[k][i]);
      metrics.max_rad[i] = std::max(metrics.max_rad[i], trajectory.values[k][i]);
    }
    if (!node.valid) {
      if (metrics.feasible) metrics.first_infeasible_line = problem.points[k].line;
      metrics.feasible = false;
      continue;
    }
    if (ranged) {
      const double range = *limits.max - *limits.min;
      const double nearest = std::min((node.lengths.array() - *limits.min).minCoeff(),
                                      (*limits.max - node.lengths.array()).minCoeff());
      metrics.min_limit_margin = std::min(metrics.min_limit_margin, nearest / range);
    }
    metrics.max_force_N[k] = node.forces.cwiseAbs().maxCoeff();
    metrics.peak_force_N = std::max(metrics.peak_force_N, metrics.max_force_N[k]);
    if (k == 0) continue;
    metrics.cumulative_energy_J[k] = metrics.cumulative_energy_J[k - 1];
    const Node& previous = trajectory.nodes[k - 1];
    if (!previous.valid) continue;
    const ActuatorVector change = node.lengths - previous.lengths;
    metrics.max_increment_mm[k] = change.cwiseAbs().maxCoeff();
    metrics.rotation_sum_deg +=
        deg_from_rad(Eigen::AngleAxisd(previous.pose.rotation.transpose() * node.pose.rotation).angle());
    metrics.increment_sum_mm += metrics.max_increment_mm[k];
    const double energy = law.step_energy_Nmm(previous, node) * kJoulePerNmm;
    metrics.energy_J += energy;
    metrics.cumulative_energy_J[k] += energy;
    metrics.required_work_J += std::abs(change.dot(node.forces)) * kJoulePerNmm;
  }
  return metrics;
}

}  // namespace pkm::redundancy
