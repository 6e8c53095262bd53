#pragma once
// The search of one greedy step (Smirnov 2019, §3.6 step 3c): the free coordinates that minimise a cost,
// from the values held so far.
//
//  - one free coordinate: a grid over the bounds, then golden-section refinement round the best grid value;
//  - three: Nelder–Mead (NLopt) from the held values, restarted from its own result (derivative-free, for the
//    non-smooth max and sum). It reaches the per-step optimum (Table 2's cases: 138.8 mm merged, 38.1 mm at
//    δ = 50°), which Smirnov's unnamed optimiser stopped 4–8 % short of. (SQP on the epigraph form min t
//    s.t. ±e_j(q) ≤ t was tried: with finite-difference gradients it stops at the first kink, 143.9 mm.)
// Holding the previous values is always a candidate, so a step is never worse than holding.
#include <nlopt.hpp>
#include <vector>

#include "redundancy/free_coordinates.hpp"

namespace pkm::redundancy {

struct GreedySettings {
  double grid_step_deg = 0.25;    ///< one free coordinate: grid spacing over the bounds
  int golden_iterations = 40;     ///< refinement of the best grid value
  double tolerance_rad = 1e-6;    ///< three: the simplex stops when the values move less than this
  double initial_step_deg = 0.1;  ///< three: size of the first simplex (steps change the angles by ~0.1°)
  int restarts = 2;               ///< three: runs of the simplex, each from the last one's result
  int max_evaluations = 2000;     ///< three: evaluations per run
};

/// What a step minimises: a candidate's cost, infinite where the candidate is not admissible.
class StepObjective {
 public:
  virtual ~StepObjective() = default;
  /// `check_branch`: a candidate across a singular position from the start counts as not admissible.
  virtual double cost(const FreeValues& values, bool check_branch) = 0;
};

class StepMinimiser {
 public:
  StepMinimiser(const FreeCoordinates& free, const GreedySettings& settings);

  /// The best values found, or `hold` where nothing found is cheaper.
  FreeValues minimise(StepObjective& objective, const FreeValues& hold);

 private:
  FreeValues minimise_1d(StepObjective& objective, const FreeValues& hold) const;
  FreeValues minimise_nd(StepObjective& objective, const FreeValues& hold);

  const FreeCoordinates& free_;
  GreedySettings settings_;
  nlopt::opt simplex_;
  std::vector<double> x_;
};

}  // namespace pkm::redundancy
