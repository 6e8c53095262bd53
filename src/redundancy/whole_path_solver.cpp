#include "redundancy/whole_path_solver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace pkm::redundancy {
namespace {

constexpr double kUnreachable = std::numeric_limits<double>::infinity();

// The states of one DP pass: per point, a list of candidate values with their nodes.
struct Layer {
  std::vector<FreeValues> values;
  std::vector<Node> nodes;
  std::vector<double> cost;  ///< best total from the start to this state
  std::vector<int> parent;
};

bool within_rate(const FreeValues& a, const FreeValues& b, int count, double step_mm,
                 const std::optional<double>& rate_rad_per_mm) {
  if (!rate_rad_per_mm) return true;
  const double allowed = *rate_rad_per_mm * step_mm + 1e-12;
  for (int i = 0; i < count; ++i) {
    if (std::abs(a[i] - b[i]) > allowed) return false;
  }
  return true;
}

// One DP pass over the given candidate values per point; point 0 keeps the start. Returns the best total and
// the chosen trajectory.
double dynamic_programming(const Problem& problem, const std::vector<std::vector<FreeValues>>& candidates,
                           const std::optional<double>& rate_rad_per_mm, Trajectory& best) {
  const LawEvaluator& law = *problem.law;
  const int count_free = law.free().count();
  const int points = static_cast<int>(problem.points.size());
  std::vector<Layer> layers(points);
  for (int k = 0; k < points; ++k) {
    Layer& layer = layers[k];
    const auto& values = candidates[k];
    const int states = static_cast<int>(values.size());
    layer.values = values;
    layer.nodes.resize(states);
    layer.cost.assign(states, kUnreachable);
    layer.parent.assign(states, -1);
    for (int s = 0; s < states; ++s) {
      if (!law.evaluate(problem.points[k], problem.loads[k], values[s], layer.nodes[s], k > 0)) continue;
      if (k == 0) {
        // The force law also pays for the start point, which it may choose (greedy_solver).
        layer.cost[s] = is_pointwise(law.options().law) ? law.step_cost(layer.nodes[s], layer.nodes[s]) : 0.0;
        continue;
      }
      const Layer& previous = layers[k - 1];
      for (int p = 0; p < static_cast<int>(previous.values.size()); ++p) {
        if (!std::isfinite(previous.cost[p])) continue;
        if (!within_rate(previous.values[p], values[s], count_free, problem.points[k].step_mm,
                         rate_rad_per_mm)) {
          continue;
        }
        const double total = previous.cost[p] + law.step_cost(previous.nodes[p], layer.nodes[s]);
        if (total < layer.cost[s]) {
          layer.cost[s] = total;
          layer.parent[s] = p;
        }
      }
    }
  }
  const Layer& last = layers.back();
  int state = -1;
  double total = kUnreachable;
  for (int s = 0; s < static_cast<int>(last.cost.size()); ++s) {
    if (last.cost[s] < total) {
      total = last.cost[s];
      state = s;
    }
  }
  if (state < 0) return kUnreachable;
  best.values.assign(points, FreeValues::Zero());
  best.nodes.assign(points, Node{});
  for (int k = points - 1; k >= 0; --k) {
    best.values[k] = layers[k].values[state];
    best.nodes[k] = layers[k].nodes[state];
    state = layers[k].parent[state];
    if (k > 0 && state < 0) return kUnreachable;
  }
  return total;
}

// Lattice of offsets {−h, 0, +h}^c round `centre`, clamped into the bounds (duplicates dropped).
std::vector<FreeValues> lattice_around(const FreeCoordinates& free, const FreeValues& centre, double h) {
  std::vector<FreeValues> values;
  const int c = free.count();
  const int size = c == 1 ? 3 : 27;
  values.reserve(size);
  values.push_back(centre);  // the current trajectory first
  for (int index = 0; index < size; ++index) {
    FreeValues v = centre;
    int code = index;
    bool zero = true;
    for (int i = 0; i < c; ++i) {
      const int offset = code % 3 - 1;
      code /= 3;
      zero = zero && offset == 0;
      v[i] = centre[i] + offset * h;
    }
    if (zero) continue;
    v = free.clamp(v);
    if (v != centre) values.push_back(v);
  }
  return values;
}

}  // namespace

Result<Trajectory> solve_whole_path(const Problem& problem, const Trajectory& initial,
                                    const WholePathSettings& settings) {
  const LawEvaluator& law = *problem.law;
  const FreeCoordinates& free = law.free();
  const int points = static_cast<int>(problem.points.size());
  const bool free_start = is_pointwise(law.options().law);
  std::optional<double> rate;
  if (settings.max_rate_deg_per_mm) rate = rad_from_deg(*settings.max_rate_deg_per_mm);

  Trajectory best = initial;
  double best_total = law_total(problem, initial);
  if (rate) {
    for (int k = 1; k < points && std::isfinite(best_total); ++k) {
      if (!within_rate(initial.values[k - 1], initial.values[k], free.count(), problem.points[k].step_mm,
                       rate)) {
        best_total = kUnreachable;  // the greedy path breaks the rate limit: DP below finds one that keeps it
      }
    }
  }

  // One free coordinate: the whole bounded range on a grid first.
  if (free.count() == 1) {
    const double step = rad_from_deg(settings.grid_step_deg);
    const int count =
        std::max(2, static_cast<int>(std::ceil((free.upper_rad(0) - free.lower_rad(0)) / step)) + 1);
    std::vector<FreeValues> grid(count, FreeValues::Zero());
    for (int i = 0; i < count; ++i)
      grid[i][0] = free.lower_rad(0) + (free.upper_rad(0) - free.lower_rad(0)) * i / (count - 1);
    std::vector<std::vector<FreeValues>> candidates(points, grid);
    if (!free_start) candidates[0] = {free.start()};
    Trajectory on_grid;
    const double total = dynamic_programming(problem, candidates, rate, on_grid);
    if (total < best_total) {
      best_total = total;
      best = std::move(on_grid);
    }
  }
  if (!std::isfinite(best_total)) {
    return make_error(ErrorCode::unreachable,
                      "the whole-path solver found no admissible trajectory of the free coordinates (bounds, "
                      "reach, singular positions or the rate limit exclude every one)");
  }

  const double final_h = rad_from_deg(settings.final_lattice_deg);
  for (double h = rad_from_deg(settings.initial_lattice_deg); h >= final_h; h *= settings.shrink) {
    for (int pass = 0; pass < settings.passes_per_lattice; ++pass) {
      std::vector<std::vector<FreeValues>> candidates(points);
      candidates[0] =
          free_start ? lattice_around(free, best.values[0], h) : std::vector<FreeValues>{free.start()};
      for (int k = 1; k < points; ++k) candidates[k] = lattice_around(free, best.values[k], h);
      Trajectory next;
      const double total = dynamic_programming(problem, candidates, rate, next);
      const bool improved = total < best_total * (1.0 - settings.relative_improvement);
      if (total <= best_total) {
        best_total = total;
        best = std::move(next);
      }
      if (!improved) break;
    }
  }
  return best;
}

}  // namespace pkm::redundancy
