#pragma once
// The weight of the moving parts as a load on the platform (Smirnov 2019: its chapter-3 statics
// count the platform's weight among the external loads; chapter 4 adds the struts).
#include "machine/machine.hpp"
#include "statics/wrench.hpp"

namespace pkm::statics {

/// Weight in N of `mass_kg` under `gravity_mm_s2`: kg · mm/s² is 10⁻³ N.
Eigen::Vector3d weight_N(double mass_kg, const Eigen::Vector3d& gravity_mm_s2);

/// The weight of the platform (at its centre of mass) plus half the weight of each strut (at its
/// platform-side joint), as a wrench about the tool point of `pose`, base frame. `struts` may be null (or
/// `strut_count` 0): then only the platform counts. The other half of each strut's weight goes to its base
/// joint and loads no actuator in this model — an approximation that treats a strut's mass as centred between
/// its joints. `pose` must be complete (reduced-DOF mechanisms: Mechanism::complete_pose).
Wrench gravity_wrench(const MassProperties& masses, const Pose& pose, const StrutJointPoints* struts,
                      int strut_count);

/// The same for a machine at a pose: completes the pose and takes the struts from Mechanism::strut_joints
/// (mechanisms without swinging struts, e.g. planar pin-jointed ones, report none: only the platform counts).
/// Fails when the pose is out of reach.
Result<Wrench> machine_gravity_wrench(const Machine& machine, const Pose& pose);

}  // namespace pkm::statics
