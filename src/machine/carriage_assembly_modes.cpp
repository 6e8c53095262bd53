#include "machine/carriage_assembly_modes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kinematics/trilateration.hpp"
#include "machine/hexapod.hpp"

namespace pkm {

namespace {

// The machine's inverse kinematics at `pose` gives `actuators` back (its strut branches agree).
bool gives_back(const Mechanism& mechanism, const Pose& pose, const ActuatorVector& actuators) {
  ActuatorVector q(actuators.size());
  if (!mechanism.actuator_values(pose, q.data())) return false;
  return (q - actuators).cwiseAbs().maxCoeff() <= 1e-6 * std::max(1.0, actuators.cwiseAbs().maxCoeff());
}

// Labels (the solutions nearest home first): 0 for the first that is the machine's own mode, then 1, 2, …
// in order. Mirror poses (the platform on the far side of the carriages) can share the mode's sign and give
// the same actuators back: the nearest to home is the machine's.
void label_modes(const Mechanism& mechanism, const ActuatorVector& actuators,
                 const std::function<bool(const Pose&)>& same_mode, std::vector<FkSolution>& solutions) {
  int next = 1;
  bool own_found = false;
  for (FkSolution& s : solutions) {
    const bool own = !own_found && gives_back(mechanism, s.pose, actuators) && same_mode(s.pose);
    own_found = own_found || own;
    s.branch = own ? 0 : next++;
  }
}

}  // namespace

Result<AssemblyModes> carriage_assembly_modes(const Mechanism& mechanism, const ActuatorVector& actuators,
                                              const std::array<Eigen::Vector3d, 6>& carriages_mm,
                                              const std::array<Eigen::Vector3d, 6>& platform_mm,
                                              const std::array<double, 6>& lengths_mm,
                                              const FkOptions& options,
                                              const std::function<bool(const Pose&)>& same_mode) {
  const Hexapod equivalent(HexapodGeometry{carriages_mm, platform_mm}, mechanism.convention(),
                           mechanism.home());
  ActuatorVector lengths(6);
  for (int j = 0; j < 6; ++j) lengths[j] = lengths_mm[j];
  auto modes = equivalent.assembly_modes(lengths, options);
  if (!modes) return modes.error();
  modes->report.method = "the Gough–Stewart platform of the carriages' joints: " + modes->report.method;
  label_modes(mechanism, actuators, same_mode, modes->solutions);
  return modes;
}

Result<AssemblyModes> three_carriage_assembly_modes(const Mechanism& mechanism,
                                                    const ActuatorVector& actuators,
                                                    const std::array<Eigen::Vector3d, 3>& carriages_mm,
                                                    const std::array<Eigen::Vector3d, 3>& platform_mm,
                                                    const std::array<double, 3>& lengths_mm,
                                                    const Eigen::Matrix3d& rotation) {
  // The tool point B is where the spheres about C_j − R b_j of radii l_j meet.
  std::array<Eigen::Vector3d, 3> centres;
  for (int j = 0; j < 3; ++j) centres[j] = carriages_mm[j] - rotation * platform_mm[j];
  const SphereIntersection meet = intersect_three_spheres(centres, lengths_mm);
  AssemblyModes modes;
  modes.report.method = "three-sphere intersection of the carriages' struts";
  modes.report.complex = meet.status == TrilaterationStatus::infeasible_lengths ? 2 : 0;
  modes.report.at_infinity = 0;
  modes.report.singular = meet.status == TrilaterationStatus::one_point ? 1 : 0;
  if (meet.status == TrilaterationStatus::collinear_centres) {
    return make_error(ErrorCode::singular,
                      "the three struts' sphere centres lie on one line: the platform can move on a circle");
  }
  for (int k = 0; k < meet.count; ++k) {
    FkSolution s;
    s.pose.position_mm = k == 0 ? meet.above_mm : meet.below_mm;
    s.pose.rotation = rotation;
    for (int j = 0; j < 3; ++j) {
      const double length = (s.pose.position_mm + rotation * platform_mm[j] - carriages_mm[j]).norm();
      s.residual_mm = std::max(s.residual_mm, std::abs(length - lengths_mm[j]));
    }
    modes.solutions.push_back(s);
  }
  // The one nearer home first.
  const Eigen::Vector3d home = mechanism.home().position_mm;
  std::sort(modes.solutions.begin(), modes.solutions.end(), [&](const FkSolution& a, const FkSolution& b) {
    return (a.pose.position_mm - home).norm() < (b.pose.position_mm - home).norm();
  });
  label_modes(
      mechanism, actuators, [](const Pose&) { return true; }, modes.solutions);
  modes.report.real = static_cast<int>(modes.solutions.size());
  return modes;
}

}  // namespace pkm
