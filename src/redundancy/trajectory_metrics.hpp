#pragma once
// What a choice of free coordinates does to the machine (eqs. (83), (86), (87)): the sum of the largest strut
// increments (∝ machining time when strut speed is the limit), the peak actuator force, the drive energy and
// the work the loads require; and what the glide scenarios weigh: the platform's total rotation and how close
// the actuators come to their limits.
#include <vector>

#include "redundancy/trajectory.hpp"

namespace pkm::redundancy {

struct TrajectoryMetrics {
  bool feasible = true;  ///< every point reachable within the limits
  int first_infeasible_line = 0;
  double increment_sum_mm = 0.0;  ///< Σ_k max_j |ΔL_jk|, (83)
  double peak_force_N = 0.0;      ///< max_k max_j |P_jk|
  double energy_J = 0.0;          ///< Σ_k Σ_j |ΔL_jk P_jk| in the law's accounting, (86)
  double required_work_J = 0.0;   ///< Σ_k |Σ_j ΔL_jk P_jk| = |work of the loads|, (87)
  double rotation_sum_deg = 0.0;  ///< Σ_k the angle of the platform's rotation from point k − 1 to k
  /// The smallest distance of any actuator from its nearer limit, as a share of its range (0.5: mid-range;
  /// NaN when the machine file gives no actuator_min and actuator_max).
  double min_limit_margin = 0.0;
  FreeValues min_rad = FreeValues::Zero();
  FreeValues max_rad = FreeValues::Zero();
  // Per point, for plots and reports (point 0 has zero increments).
  std::vector<double> max_increment_mm;
  std::vector<double> max_force_N;
  std::vector<double> cumulative_energy_J;
};

TrajectoryMetrics measure(const Problem& problem, const Trajectory& trajectory);

}  // namespace pkm::redundancy
