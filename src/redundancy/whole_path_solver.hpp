#pragma once
// A whole-path optimum Smirnov does not have: dynamic programming over the free coordinates of all points at
// once, minimising the law's total (Σ_k max_j |ΔL_jk| for the increment law, which is exactly the machining
// time metric (83); Σ energy; Σ peak force) instead of each step greedily.
//
// One free coordinate: DP over a fine grid of the whole bounded range (global on the grid), then refined.
// Three: iterated dynamic programming (Luus): DP over a lattice of offsets {−h, 0, +h}³ round the current
// trajectory, the lattice shrinking as the total stops improving. The current trajectory is always on the
// lattice, so every pass is at least as good as the last; started from the greedy solution, the result is
// never worse than greedy.
//
// An optional rate limit bounds how fast the free coordinates may change per mm of path, so that the
// optimum stays smooth enough for the machine (Smirnov 2019 has none).
#include <optional>

#include "core/result.hpp"
#include "redundancy/trajectory.hpp"

namespace pkm::redundancy {

struct WholePathSettings {
  double grid_step_deg = 0.25;         ///< one free coordinate: full-range grid spacing
  double initial_lattice_deg = 0.5;    ///< offsets of the first lattice
  double final_lattice_deg = 1e-4;     ///< stop when the lattice is finer than this
  double shrink = 0.25;                ///< lattice factor when a pass no longer improves
  double relative_improvement = 1e-9;  ///< a pass "improves" when the total drops by more than this share
  int passes_per_lattice = 3;          ///< DP passes at one lattice size while they keep improving
  std::optional<double> max_rate_deg_per_mm;  ///< |Δq| ≤ this · step length, every coordinate
};

/// `initial` must be admissible (the greedy solution).
Result<Trajectory> solve_whole_path(const Problem& problem, const Trajectory& initial,
                                    const WholePathSettings& settings);

}  // namespace pkm::redundancy
