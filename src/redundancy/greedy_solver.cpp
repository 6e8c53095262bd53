#include "redundancy/greedy_solver.hpp"

#include <fmt/format.h>

#include <limits>

namespace pkm::redundancy {
namespace {

// The law's cost of the step from a fixed node to the candidate at one point.
class PointStep final : public StepObjective {
 public:
  PointStep(const Problem& problem, const Node& from, int to_index)
      : problem_(problem), from_(from), to_index_(to_index) {}

  double cost(const FreeValues& values, bool check_branch) override {
    const LawEvaluator& law = *problem_.law;
    if (!law.evaluate(problem_.points[to_index_], problem_.loads[to_index_], values, node_, check_branch))
      return std::numeric_limits<double>::infinity();
    return law.step_cost(from_, node_);
  }

 private:
  const Problem& problem_;
  const Node& from_;
  int to_index_;
  Node node_;
};

}  // namespace

Result<Trajectory> solve_greedy(const Problem& problem, const GreedySettings& settings,
                                const std::string& source) {
  const LawEvaluator& law = *problem.law;
  const FreeCoordinates& free = law.free();
  const int count = static_cast<int>(problem.points.size());
  Trajectory trajectory;
  trajectory.values.resize(count);
  trajectory.nodes.resize(count);
  StepMinimiser search(free, settings);
  trajectory.values[0] = free.start();
  if (is_pointwise(law.options().law)) {
    // The force law is pointwise: the start is chosen like any other point (the leading rapid goes there).
    Node unused;
    law.evaluate(problem.points[0], problem.loads[0], free.start(), unused, false);
    PointStep first(problem, unused, 0);
    trajectory.values[0] = search.minimise(first, free.start());
  }
  if (!law.evaluate(problem.points[0], problem.loads[0], trajectory.values[0], trajectory.nodes[0], false)) {
    return make_error(
        ErrorCode::unreachable,
        fmt::format("{}:{}: the start pose is out of reach or over a limit", source, problem.points[0].line));
  }
  for (int k = 0; k + 1 < count; ++k) {
    PointStep step(problem, trajectory.nodes[k], k + 1);
    const bool reset = !problem.reset.empty() && problem.reset[static_cast<std::size_t>(k + 1)];
    const FreeValues chosen = reset ? free.start() : search.minimise(step, trajectory.values[k]);
    Node& node = trajectory.nodes[k + 1];
    if (!law.evaluate(problem.points[k + 1], problem.loads[k + 1], chosen, node, true)) {
      return make_error(
          ErrorCode::unreachable,
          fmt::format("{}:{}: no admissible {} within the bounds at ({:.3f}, {:.3f}, {:.3f}) mm: "
                      "every candidate is out of reach, over a limit or across a singular position",
                      source, problem.points[k + 1].line, free.name(0), problem.points[k + 1].position_mm.x(),
                      problem.points[k + 1].position_mm.y(), problem.points[k + 1].position_mm.z()));
    }
    trajectory.values[k + 1] = chosen;
  }
  return trajectory;
}

}  // namespace pkm::redundancy
