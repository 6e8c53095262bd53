#include "redundancy/greedy_solver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <optional>

#include "core/units.hpp"

namespace pkm::redundancy {
namespace {

constexpr double kInfeasibleCost = std::numeric_limits<double>::infinity();

struct StepContext {
  const Problem& problem;
  const Node& from;
  int to_index;
};

double candidate_cost(const StepContext& step, const FreeValues& values, Node& node, bool check_branch) {
  const LawEvaluator& law = *step.problem.law;
  if (!law.evaluate(step.problem.points[step.to_index], step.problem.loads[step.to_index], values, node,
                    check_branch)) {
    return kInfeasibleCost;
  }
  return law.step_cost(step.from, node);
}

// One free coordinate: grid, then golden section round the best grid point.
FreeValues solve_step_1d(const StepContext& step, const FreeValues& hold, const GreedySettings& settings) {
  const FreeCoordinates& free = step.problem.law->free();
  const double lower = free.lower_rad(0);
  const double upper = free.upper_rad(0);
  const double grid = rad_from_deg(settings.grid_step_deg);
  const int count = std::max(2, static_cast<int>(std::ceil((upper - lower) / grid)) + 1);
  Node node;
  FreeValues best = hold;
  double best_cost = candidate_cost(step, hold, node, true);
  FreeValues values = hold;
  double best_grid = hold[0];
  for (int i = 0; i < count; ++i) {
    values[0] = lower + (upper - lower) * i / (count - 1);
    const double cost = candidate_cost(step, values, node, true);
    if (cost < best_cost) {
      best_cost = cost;
      best = values;
      best_grid = values[0];
    }
  }
  if (!std::isfinite(best_cost)) return best;
  // Golden section on [best − h, best + h]: the cost is unimodal there for grids finer than its features.
  const double h = (upper - lower) / (count - 1);
  double a = std::max(lower, best_grid - h);
  double b = std::min(upper, best_grid + h);
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - ratio * (b - a);
  double d = a + ratio * (b - a);
  FreeValues vc = hold;
  FreeValues vd = hold;
  vc[0] = c;
  vd[0] = d;
  double fc = candidate_cost(step, vc, node, true);
  double fd = candidate_cost(step, vd, node, true);
  for (int it = 0; it < settings.golden_iterations; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - ratio * (b - a);
      vc[0] = c;
      fc = candidate_cost(step, vc, node, true);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + ratio * (b - a);
      vd[0] = d;
      fd = candidate_cost(step, vd, node, true);
    }
  }
  // The swaps above move c and d without their value vectors: set those to the final points.
  vc[0] = c;
  vd[0] = d;
  if (fc < best_cost) {
    best_cost = fc;
    best = vc;
  }
  if (fd < best_cost) best = vd;
  return best;
}

// Three free coordinates: Nelder–Mead on the step cost (it is a max or a sum of absolute values, so not
// smooth), restarted from its own result so that a collapsed simplex cannot stop it early.
struct SimplexData {
  const StepContext* step;
  Node node;
};

double simplex_objective(unsigned n, const double* x, double* /*grad*/, void* raw) {
  auto& data = *static_cast<SimplexData*>(raw);
  FreeValues values = FreeValues::Zero();
  for (unsigned i = 0; i < n; ++i) values[i] = x[i];
  constexpr double kUnreachablePenalty = 1e12;  // NLopt wants finite values
  return std::min(kUnreachablePenalty, candidate_cost(*data.step, values, data.node, false));
}

class SimplexSearch {
 public:
  SimplexSearch(const FreeCoordinates& free, const GreedySettings& settings)
      : optimizer_(nlopt::LN_NELDERMEAD, static_cast<unsigned>(free.count())), x_(free.count()) {
    std::vector<double> lower(free.count());
    std::vector<double> upper(free.count());
    for (int i = 0; i < free.count(); ++i) {
      lower[i] = free.lower_rad(i);
      upper[i] = free.upper_rad(i);
    }
    optimizer_.set_lower_bounds(lower);
    optimizer_.set_upper_bounds(upper);
    optimizer_.set_xtol_abs(settings.tolerance_rad);
    optimizer_.set_maxeval(settings.max_evaluations);
    optimizer_.set_initial_step(rad_from_deg(settings.initial_step_deg));
    restarts_ = settings.restarts;
  }

  FreeValues minimise(const StepContext& step, const FreeValues& start) {
    SimplexData data{&step, {}};
    optimizer_.set_min_objective(simplex_objective, &data);
    for (std::size_t i = 0; i < x_.size(); ++i) x_[i] = start[static_cast<int>(i)];
    for (int run = 0; run < restarts_; ++run) {
      double value = 0.0;
      try {
        optimizer_.optimize(x_, value);
      } catch (const std::exception&) {
        // Round-off: x_ holds the best point so far, judged by the caller like any candidate.
      }
    }
    FreeValues result = start;
    for (std::size_t i = 0; i < x_.size(); ++i) result[static_cast<int>(i)] = x_[i];
    return result;
  }

 private:
  nlopt::opt optimizer_;
  std::vector<double> x_;
  int restarts_ = 2;
};

FreeValues solve_step_nd(const StepContext& step, const FreeValues& hold, SimplexSearch& search) {
  Node node;
  const FreeValues candidate = search.minimise(step, hold);
  return candidate_cost(step, candidate, node, true) < candidate_cost(step, hold, node, true) ? candidate
                                                                                              : hold;
}

}  // namespace

Result<Trajectory> solve_greedy(const Problem& problem, const GreedySettings& settings,
                                const std::string& source) {
  const LawEvaluator& law = *problem.law;
  const FreeCoordinates& free = law.free();
  const int count = static_cast<int>(problem.points.size());
  Trajectory trajectory;
  trajectory.values.resize(count);
  trajectory.nodes.resize(count);
  std::optional<SimplexSearch> search;
  if (free.count() > 1) search.emplace(free, settings);
  trajectory.values[0] = free.start();
  if (is_pointwise(law.options().law)) {
    // The force law is pointwise: the start is chosen like any other point (the leading rapid goes there).
    Node unused;
    law.evaluate(problem.points[0], problem.loads[0], free.start(), unused, false);
    const StepContext first{problem, unused, 0};
    trajectory.values[0] = free.count() == 1 ? solve_step_1d(first, free.start(), settings)
                                             : solve_step_nd(first, free.start(), *search);
  }
  if (!law.evaluate(problem.points[0], problem.loads[0], trajectory.values[0], trajectory.nodes[0], false)) {
    return make_error(
        ErrorCode::unreachable,
        fmt::format("{}:{}: the start pose is out of reach or over a limit", source, problem.points[0].line));
  }
  for (int k = 0; k + 1 < count; ++k) {
    const StepContext step{problem, trajectory.nodes[k], k + 1};
    const FreeValues hold = trajectory.values[k];
    FreeValues chosen;
    if (free.count() == 1) {
      chosen = solve_step_1d(step, hold, settings);
    } else {
      chosen = solve_step_nd(step, hold, *search);
    }
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
