#pragma once
// Smirnov 2019's scheme (§3.6): walk the path and, at every step k → k+1, choose the free coordinates
// at k+1 that minimise the law's cost of that step, with k fixed.
//
//  - one free coordinate: a grid over the bounds, then golden-section refinement round the best grid value;
//  - three: Nelder–Mead (NLopt) from the previous values, restarted from its own result (derivative-free,
//    for the non-smooth max and sum). It reaches the per-step optimum (Table 2's cases: 138.8 mm merged, 38.1
//    mm at δ = 50°), which Smirnov's unnamed optimiser stopped 4–8 % short of. (SQP on the epigraph form min
//    t s.t. ±e_j(q) ≤ t was tried: with finite-difference gradients it stops at the first kink, 143.9 mm.)
// Holding the previous values is always a candidate, so the law is never worse than holding on a step.
#include "core/result.hpp"
#include "redundancy/trajectory.hpp"

namespace pkm::redundancy {

struct GreedySettings {
  double grid_step_deg = 0.25;    ///< one free coordinate: grid spacing over the bounds
  int golden_iterations = 40;     ///< refinement of the best grid value
  double tolerance_rad = 1e-6;    ///< three: the simplex stops when the values move less than this
  double initial_step_deg = 0.1;  ///< three: size of the first simplex (steps change the angles by ~0.1°)
  int restarts = 2;               ///< three: runs of the simplex, each from the last one's result
  int max_evaluations = 2000;     ///< three: evaluations per run
};

/// Errors name the program line of the first point where no admissible free coordinates exist.
Result<Trajectory> solve_greedy(const Problem& problem, const GreedySettings& settings,
                                const std::string& source);

}  // namespace pkm::redundancy
