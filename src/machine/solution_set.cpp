#include "machine/solution_set.hpp"

#include <algorithm>

namespace pkm {

bool contains_solution(const std::vector<FkSolution>& solutions, const Pose& pose) {
  return std::any_of(solutions.begin(), solutions.end(), [&pose](const FkSolution& s) {
    const PoseDistance d = pose_distance(s.pose, pose);
    return d.position_mm < kSameSolutionPosition_mm && d.rotation_rad < kSameSolutionRotation_rad;
  });
}

void sort_nearest_to(std::vector<FkSolution>& solutions, const Pose& home, double rotation_weight_mm) {
  auto distance = [&](const FkSolution& s) {
    const PoseDistance d = pose_distance(s.pose, home);
    return d.position_mm + rotation_weight_mm * d.rotation_rad;
  };
  std::stable_sort(solutions.begin(), solutions.end(),
                   [&](const FkSolution& a, const FkSolution& b) { return distance(a) < distance(b); });
}

}  // namespace pkm
