#pragma once
// Collecting the assembly modes that forward_all() finds: the same solution reached twice counts once, and
// the list is ordered nearest to home first (the one a warm-started solver would give from home).
#include <vector>

#include "machine/mechanism.hpp"

namespace pkm {

/// Two solutions closer than this in position and rotation are the same assembly (both well above the FK
/// tolerance's effect on the pose, well below any distance between distinct assemblies).
constexpr double kSameSolutionPosition_mm = 1e-6;
constexpr double kSameSolutionRotation_rad = 1e-8;

bool contains_solution(const std::vector<FkSolution>& solutions, const Pose& pose);

/// Sorts by |Δposition| + radius·|Δrotation| from home; `rotation_weight_mm` is a characteristic radius of
/// the platform (how far its joints move per radian).
void sort_nearest_to(std::vector<FkSolution>& solutions, const Pose& home, double rotation_weight_mm);

}  // namespace pkm
