#pragma once
// Rigid-body inverse dynamics of any mechanism through the Mechanism interface (exact, where Smirnov
// 2019, §4.3 linearises): the drive forces that move the platform with a given twist and twist rate against
// gravity and an external load.
//
// Bodies: the platform with its payload; per strut a lower part turning about the base joint A_j and an upper
// part sliding on it, at the platform joint B_j (constant-length struts: the lower part alone), both turning
// with the strut's angular velocity perpendicular to its axis, ω_j = u_j × u̇_j (spin about the axis is not
// modelled); per moving base joint a carriage (a point mass at A_j). Their velocities follow from the
// platform twist and from the base joints' motion (Mechanism::base_joint_motion).
//
// The equations are Newton–Euler with virtual power: for each twist the mechanism allows per unit rate of a
// controlled coordinate (Mechanism::controlled_twists), the power of the drive forces equals the power of the
// bodies' rates of momentum less gravity and the external load:
//   J_cᵀ P = Σ_bodies (m a_c − m g)·v_c,k + (I α + ω × I ω)·ω_k − w_ext·t_k,   k = 1…m,
// with J_c = Mechanism::twist_jacobian · T_c. Splitting the right-hand side gives P = P_static + P_dynamic
// (Smirnov 2019, §4.4): the static part (gravity and load) is what statics gives for the same bodies at rest.
//
// Units: mm, kg, s inside; forces leave in N (angular actuators: N·mm), energies in J.
#include "core/pose.hpp"
#include "core/result.hpp"
#include "machine/dynamics_parameters.hpp"
#include "machine/mechanism.hpp"
#include "statics/wrench.hpp"

namespace pkm::dynamics {

/// The platform's motion at one instant: a complete pose, the twist about the tool point and its rate.
struct PlatformMotion {
  Pose pose;
  Eigen::Vector3d velocity_mm_s = Eigen::Vector3d::Zero();           ///< of the tool point
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();  ///< base frame
  Eigen::Vector3d acceleration_mm_s2 = Eigen::Vector3d::Zero();      ///< of the tool point
  Eigen::Vector3d angular_acceleration_rad_s2 = Eigen::Vector3d::Zero();
};

/// Drive forces (N; N·mm for angular actuators), positive when the drive pushes its coordinate up.
struct DriveForces {
  ActuatorVector total;
  ActuatorVector static_part;     ///< gravity and the external load
  ActuatorVector dynamic_part;    ///< the rates of momentum
  ActuatorVector actuator_rates;  ///< q̇ (mm/s or rad/s), for the drive power P·q̇
};

/// The drive forces for `motion` (whose pose must be complete and reachable) under the external `load` on the
/// platform (moment about the tool point). Fails where the pose is out of reach, or singular: the drives
/// cannot hold the platform there.
Result<DriveForces> inverse_dynamics(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                     const PlatformMotion& motion, const statics::Wrench& load = {});

/// Kinetic energy of every moving body at `motion` (accelerations unused), J.
Result<double> kinetic_energy_J(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                const PlatformMotion& motion);

/// Potential energy of the bodies in gravity, −Σ m g·c, J (zero at the base frame's origin).
Result<double> gravity_potential_J(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                   const Pose& pose);

}  // namespace pkm::dynamics
