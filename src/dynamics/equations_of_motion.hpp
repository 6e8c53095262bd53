#pragma once
// The rigid-body equations of motion of a mechanism in the coordinates of a twist basis B (columns: platform
// twists per unit coordinate rate): with twist t = B ċ and twist rate ṫ = B c̈ (B constant, as for the free
// platform's own twist coordinates),
//   M(pose) c̈ + bias(pose, t) = applied(pose) + J_Bᵀ P,   J_B = Mechanism::twist_jacobian · B,
// where P are the forces along the struts (drives, or elastic struts). Units: mm, kg, s; generalised forces
// in kg·mm/s² per unit coordinate (N = 10³ kg·mm/s²), P in N. Built on the same bodies as rigid_dynamics.hpp.
#include "core/result.hpp"
#include "dynamics/body_motion.hpp"
#include "statics/wrench.hpp"

namespace pkm::dynamics {

using Twist = Eigen::Matrix<double, 6, 1>;
using CoordinateMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

/// The twist basis in which a platform moves freely: all six twist components for mechanisms that control
/// the whole pose, (v_x, v_y, ω_z) for planar ones. False for reduced-DOF spatial mechanisms (tripod,
/// tricept), whose allowed twists turn with the pose.
bool platform_twist_basis(const Mechanism& mechanism, TwistBasis& basis);

/// Per coordinate of the basis: the power of the bodies' rates of momentum (dynamic) and of gravity and the
/// load (applied) in the twist of that coordinate, kg·mm/s² (load in N, N·mm).
struct CoordinateForces {
  ActuatorVector dynamic;
  ActuatorVector applied;
};
CoordinateForces coordinate_forces(const MechanismState& state, const DynamicsParameters& parameters,
                                   const TwistBasis& basis, const Twist& twist, const Twist& twist_rate,
                                   const statics::Wrench& load);

struct EquationsOfMotion {
  CoordinateMatrix mass;          ///< kg (mm coordinates) / kg·mm² (rad coordinates)
  ActuatorVector bias;            ///< velocity-product terms, kg·mm/s²
  ActuatorVector applied;         ///< gravity and the load, kg·mm/s²
  JacobianMatrix drive_jacobian;  ///< J_B: actuator rates per coordinate rate
  MechanismState state;
};

/// The equations at `pose` moving with `twist` (which must lie in the basis' span).
Result<EquationsOfMotion> equations_of_motion(const Mechanism& mechanism,
                                              const DynamicsParameters& parameters, const Pose& pose,
                                              const TwistBasis& basis, const Twist& twist,
                                              const statics::Wrench& load = {});

}  // namespace pkm::dynamics
