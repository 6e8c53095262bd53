#pragma once
// Smirnov 2019's scheme (§3.6): walk the path and, at every step k → k+1, choose the free coordinates
// at k+1 that minimise the law's cost of that step, with k fixed (the search: step_minimiser.hpp).
#include "core/result.hpp"
#include "redundancy/step_minimiser.hpp"
#include "redundancy/trajectory.hpp"

namespace pkm::redundancy {

/// Errors name the program line of the first point where no admissible free coordinates exist.
Result<Trajectory> solve_greedy(const Problem& problem, const GreedySettings& settings,
                                const std::string& source);

}  // namespace pkm::redundancy
