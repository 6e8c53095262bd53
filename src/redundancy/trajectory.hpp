#pragma once
// A redundancy problem (path points, loads, law) and a solution: the free coordinates at every point.
#include <vector>

#include "redundancy/law.hpp"

namespace pkm::redundancy {

struct Problem {
  const LawEvaluator* law = nullptr;
  std::vector<PathPoint> points;       ///< points[0] is fixed at the start values
  std::vector<statics::Wrench> loads;  ///< external load at each point (about the tool point)
  /// Points where the free coordinates return to their start values rather than being chosen (the seeds'
  /// forming study returns the angles to zero at each plane); empty: none.
  std::vector<char> reset;
};

struct Trajectory {
  std::vector<FreeValues> values;  ///< rad, one per point
  std::vector<Node> nodes;         ///< evaluated at `values`
};

/// The free coordinates held at their start values (Smirnov 2019 baseline). Nodes that cannot be
/// reached are left invalid; the metrics say so.
Trajectory constant_trajectory(const Problem& problem);

/// The law's total along a trajectory: Σ step costs (increment, energy) or Σ node costs (force).
double law_total(const Problem& problem, const Trajectory& trajectory);

}  // namespace pkm::redundancy
