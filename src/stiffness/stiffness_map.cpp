#include "stiffness/stiffness_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "dynamics/map_point_counts.hpp"
#include "dynamics/pose_grid_columns.hpp"

namespace pkm::stiffness {
namespace {

constexpr double kStiffnessMapNPerUmPerNPerMm = 1e-3;

using dynamics::MapPointStatus;

// Whether an error of the model is about the pose (a map cell without a value) or about the model.
bool stiffness_map_cell_status(ErrorCode code, MapPointStatus& status) {
  switch (code) {
    case ErrorCode::unreachable:
    case ErrorCode::wrong_branch:
      status = MapPointStatus::unreachable;
      return true;
    case ErrorCode::limit_exceeded:
      status = MapPointStatus::out_of_range;
      return true;
    case ErrorCode::singular:
    case ErrorCode::not_converged:
      status = MapPointStatus::singular;
      return true;
    default:
      return false;
  }
}

}  // namespace

ComplianceAtPose strut_compliance_at(const Machine& machine, const StiffnessParameters& stiffness) {
  return [&machine, &stiffness](const Pose& pose) -> Result<ToolCompliance> {
    auto actuators = machine.mechanism->inverse(pose);
    if (!actuators) return actuators.error();
    if (Status in_range = check_actuator_range(machine, *actuators); !in_range) return in_range.error();
    return strut_compliance(*machine.mechanism, stiffness, pose);
  };
}

StiffnessMapPoint lowest_translational_stiffness(const ToolCompliance& compliance) {
  const PrincipalStiffness principal = principal_stiffness(compliance, false);
  StiffnessMapPoint point;
  point.status = MapPointStatus::ok;
  point.lowest_stiffness_N_um = principal.stiffness[0] * kStiffnessMapNPerUmPerNPerMm;
  // An eigenvector's sign is arbitrary: the largest component positive makes the map reproducible.
  Eigen::Vector3d d = principal.directions.col(0).normalized();
  Eigen::Index largest = 0;
  d.cwiseAbs().maxCoeff(&largest);
  if (d[largest] < 0.0) d = -d;
  point.direction = d;
  return point;
}

Result<std::vector<StiffnessMapPoint>> stiffness_map(const std::vector<Pose>& poses,
                                                     const ComplianceAtPose& compliance) {
  std::vector<StiffnessMapPoint> points;
  points.reserve(poses.size());
  for (const Pose& pose : poses) {
    auto c = compliance(pose);
    if (c) {
      points.push_back(lowest_translational_stiffness(*c));
      continue;
    }
    StiffnessMapPoint none;
    if (!stiffness_map_cell_status(c.error().code, none.status)) return c.error();
    points.push_back(none);
  }
  return points;
}

StiffnessMapSummary summarise_stiffness_map(const std::vector<StiffnessMapPoint>& points) {
  return dynamics::count_map_points(points,
                                    [](const StiffnessMapPoint& p) { return p.lowest_stiffness_N_um; });
}

}  // namespace pkm::stiffness
