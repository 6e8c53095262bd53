#include "redundancy/step_minimiser.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/units.hpp"

namespace pkm::redundancy {
namespace {

struct SimplexData {
  StepObjective* objective;
};

double simplex_objective(unsigned n, const double* x, double* /*grad*/, void* raw) {
  auto& data = *static_cast<SimplexData*>(raw);
  FreeValues values = FreeValues::Zero();
  for (unsigned i = 0; i < n; ++i) values[static_cast<int>(i)] = x[i];
  constexpr double kUnreachablePenalty = 1e12;  // NLopt wants finite values
  return std::min(kUnreachablePenalty, data.objective->cost(values, false));
}

}  // namespace

StepMinimiser::StepMinimiser(const FreeCoordinates& free, const GreedySettings& settings)
    : free_(free),
      settings_(settings),
      simplex_(nlopt::LN_NELDERMEAD, static_cast<unsigned>(free.count())),
      x_(free.count()) {
  std::vector<double> lower(free.count());
  std::vector<double> upper(free.count());
  for (int i = 0; i < free.count(); ++i) {
    lower[i] = free.lower_rad(i);
    upper[i] = free.upper_rad(i);
  }
  simplex_.set_lower_bounds(lower);
  simplex_.set_upper_bounds(upper);
  simplex_.set_xtol_abs(settings.tolerance_rad);
  simplex_.set_maxeval(settings.max_evaluations);
  simplex_.set_initial_step(rad_from_deg(settings.initial_step_deg));
}

FreeValues StepMinimiser::minimise(StepObjective& objective, const FreeValues& hold) {
  return free_.count() == 1 ? minimise_1d(objective, hold) : minimise_nd(objective, hold);
}

// One free coordinate: grid, then golden section round the best grid point.
FreeValues StepMinimiser::minimise_1d(StepObjective& objective, const FreeValues& hold) const {
  const double lower = free_.lower_rad(0);
  const double upper = free_.upper_rad(0);
  const double grid = rad_from_deg(settings_.grid_step_deg);
  const int count = std::max(2, static_cast<int>(std::ceil((upper - lower) / grid)) + 1);
  FreeValues best = hold;
  double best_cost = objective.cost(hold, true);
  FreeValues values = hold;
  double best_grid = hold[0];
  for (int i = 0; i < count; ++i) {
    values[0] = lower + (upper - lower) * i / (count - 1);
    const double cost = objective.cost(values, true);
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
  double fc = objective.cost(vc, true);
  double fd = objective.cost(vd, true);
  for (int it = 0; it < settings_.golden_iterations; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - ratio * (b - a);
      vc[0] = c;
      fc = objective.cost(vc, true);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + ratio * (b - a);
      vd[0] = d;
      fd = objective.cost(vd, true);
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

// Three free coordinates: Nelder–Mead on the cost (a max or a sum of absolute values, so not smooth),
// restarted from its own result so that a collapsed simplex cannot stop it early; judged against holding
// with the branch checked.
FreeValues StepMinimiser::minimise_nd(StepObjective& objective, const FreeValues& hold) {
  SimplexData data{&objective};
  simplex_.set_min_objective(simplex_objective, &data);
  for (std::size_t i = 0; i < x_.size(); ++i) x_[i] = hold[static_cast<int>(i)];
  for (int run = 0; run < settings_.restarts; ++run) {
    double value = 0.0;
    try {
      simplex_.optimize(x_, value);
    } catch (const std::exception&) {
      // Round-off: x_ holds the best point so far, judged below like any candidate.
    }
  }
  FreeValues candidate = hold;
  for (std::size_t i = 0; i < x_.size(); ++i) candidate[static_cast<int>(i)] = x_[i];
  return objective.cost(candidate, true) < objective.cost(hold, true) ? candidate : hold;
}

}  // namespace pkm::redundancy
