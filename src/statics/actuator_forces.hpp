#pragma once
// Quasi-static actuator forces: what the drives must exert to hold the platform against a load, with no
// friction and no inertia (Smirnov 2019, (73) planar, §3.3; (91) hexapod, §3.5.2).
//
// Sign ((73)/(84)): P_j > 0 means actuator j pushes the platform (strut in compression); it then does
// positive work when it lengthens. By virtual work,  Σ_j P_j dL_j = −(F · dp + M · dθ).
// Units: N for linear actuators, N·mm for angular ones (rotopod carriages on a circle).
#include "machine/mechanism.hpp"
#include "statics/wrench.hpp"

namespace pkm::statics {

/// Below this ratio of the smallest to the largest LU pivot of the column-equilibrated Jacobian the pose
/// counts as singular: the forces would be dominated by rounding (they grow like 1/ratio times the load).
constexpr double kSingularPivotRatio = 1e-9;

/// Actuator forces that hold the platform against `load` (acting on the platform, moment about the tool point
/// of the completed pose, base frame): generalised forces Q = T_cᵀ w (coordinate_twist.hpp), then
/// J_cᵀ P = −Q with J_c = Mechanism::jacobian, i.e. (73)/(91) in the mechanism's controlled coordinates. For
/// a reduced-DOF mechanism the wrench components its constraints carry (a planar machine's out-of-plane load,
/// a tricept's central leg) do no work and do not load the actuators.
/// Errors: unreachable (the pose cannot be completed or reached); singular (the Jacobian cannot be inverted,
/// also at the angle convention's own singularity, e.g. abc at B = ±90°, where angle rates cannot describe
/// every rotation: twist_actuator_forces has no such limit); unsupported (a mechanism with more or fewer
/// actuators than controlled coordinates).
Result<ActuatorVector> actuator_forces(const Mechanism& mechanism, const Pose& pose, const Wrench& load);

/// Hot path for mechanisms with six actuators and a 6 × 6 twist Jacobian (Mechanism::twist_jacobian:
/// hexapods, rotopod, hexaglide): J_tᵀ P = −w, rows of J_t the actuators' lines about the tool point ((91)
/// for struts), a fixed-size 6 × 6 LU; no allocation. Writes six forces (N, N·mm for angular actuators) and
/// returns true; returns false, leaving `forces_N` unspecified, when the pose is singular
/// (kSingularPivotRatio), out of reach, or the mechanism has no square twist Jacobian.
bool twist_actuator_forces(const Mechanism& mechanism, const Pose& pose, const Wrench& load,
                           double* forces_N) noexcept;

}  // namespace pkm::statics
