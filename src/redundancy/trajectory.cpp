#include "redundancy/trajectory.hpp"

#include <limits>

namespace pkm::redundancy {

Trajectory constant_trajectory(const Problem& problem) {
  const FreeCoordinates& free = problem.law->free();
  const int count = static_cast<int>(problem.points.size());
  Trajectory trajectory;
  trajectory.values.assign(count, free.start());
  trajectory.nodes.resize(count);
  for (int k = 0; k < count; ++k) {
    problem.law->evaluate(problem.points[k], problem.loads[k], free.start(), trajectory.nodes[k], false);
  }
  return trajectory;
}

double law_total(const Problem& problem, const Trajectory& trajectory) {
  if (trajectory.nodes.empty() || !trajectory.nodes[0].valid) return std::numeric_limits<double>::infinity();
  // A pointwise law pays for every point, the start included; the step laws for every step.
  double total = is_pointwise(problem.law->options().law)
                     ? problem.law->step_cost(trajectory.nodes[0], trajectory.nodes[0])
                     : 0.0;
  for (std::size_t k = 1; k < trajectory.nodes.size(); ++k) {
    if (!trajectory.nodes[k].valid || !trajectory.nodes[k - 1].valid)
      return std::numeric_limits<double>::infinity();
    total += problem.law->step_cost(trajectory.nodes[k - 1], trajectory.nodes[k]);
  }
  return total;
}

}  // namespace pkm::redundancy
