#include "statics/gravity.hpp"

#include <Eigen/Geometry>

namespace pkm::statics {

Eigen::Vector3d weight_N(double mass_kg, const Eigen::Vector3d& gravity_mm_s2) {
  return mass_kg * gravity_mm_s2 * 1e-3;
}

Wrench gravity_wrench(const MassProperties& masses, const Pose& pose, const StrutJointPoints* struts,
                      int strut_count) {
  Wrench w;
  const Eigen::Vector3d platform = weight_N(masses.platform_kg, masses.gravity_mm_s2);
  w.force_N += platform;
  w.moment_Nmm += (pose.rotation * masses.platform_com_mm).cross(platform);
  if (struts == nullptr || !(masses.strut_kg > 0.0)) return w;
  const Eigen::Vector3d half_strut = weight_N(0.5 * masses.strut_kg, masses.gravity_mm_s2);
  for (int j = 0; j < strut_count && j < kMaxActuators; ++j) {
    w.force_N += half_strut;
    w.moment_Nmm += (struts->platform_mm[j] - pose.position_mm).cross(half_strut);
  }
  return w;
}

Result<Wrench> machine_gravity_wrench(const Machine& machine, const Pose& pose) {
  const Mechanism& mechanism = *machine.mechanism;
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  StrutJointPoints struts;
  const int count = mechanism.strut_joints(*completed, struts);
  if (count < 0) {
    return make_error(ErrorCode::unreachable, "gravity: the struts cannot reach this pose");
  }
  return gravity_wrench(machine.masses, *completed, count > 0 ? &struts : nullptr, count);
}

}  // namespace pkm::statics
