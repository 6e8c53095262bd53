#pragma once
// A map of the tool's static stiffness over the workspace (the lowest stiffness
// direction and value per grid cell, in CSV and the HTML report): at each pose of a grid
// (dynamics/pose_grid.hpp) the weakest principal translational stiffness (principal_stiffness of the
// compliance: the inverse of the translational block's largest eigenvalue) and its direction, or the reason
// there is none (out of reach, beyond the drives' range, singular). The compliance comes from any model
// through a function of the pose, so the strut-only model (strut_compliance.hpp) and fuller ones (joints,
// frame) give maps the same way.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "dynamics/frequency_map.hpp"
#include "machine/machine.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

/// A compliance model: the compliance at a pose, or an error whose code says why there is none
/// (unreachable, limit_exceeded, singular / not_converged; any other code stops the map).
using ComplianceAtPose = std::function<Result<ToolCompliance>(const Pose&)>;

/// The strut-only model of `machine` with `stiffness`, the drives' range checked first (as
/// `pkm compliance --pose` and the frequency map do: limit_exceeded where the actuators leave it). The
/// machine and the parameters must outlive the function.
ComplianceAtPose strut_compliance_at(const Machine& machine, const StiffnessParameters& stiffness);

struct StiffnessMapPoint {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double lowest_stiffness_N_um = kNone;  ///< NaN unless status is ok; infinite if no translation is allowed
  /// Unit direction of the weakest translation, base frame, its largest component positive (NaN unless ok).
  Eigen::Vector3d direction = Eigen::Vector3d::Constant(kNone);
  dynamics::MapPointStatus status = dynamics::MapPointStatus::singular;
};

/// The weakest translational stiffness of one compliance (what each map cell holds).
StiffnessMapPoint lowest_translational_stiffness(const ToolCompliance& compliance);

/// The map over `poses`. Fails only for an error of the model that is not about a pose (bad_input,
/// unsupported, io), with that error.
Result<std::vector<StiffnessMapPoint>> stiffness_map(const std::vector<Pose>& poses,
                                                     const ComplianceAtPose& compliance);

using StiffnessMapSummary = dynamics::MapPointCounts;
StiffnessMapSummary summarise_stiffness_map(const std::vector<StiffnessMapPoint>& points);

}  // namespace pkm::stiffness
