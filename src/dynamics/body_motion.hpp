#pragma once
// The moving bodies of a mechanism at one pose and how they move with the platform (rigid_dynamics.hpp says
// which bodies). Everything here is in mm, kg, s; nothing allocates.
#include <array>

#include "core/result.hpp"
#include "dynamics/strut_rows.hpp"
#include "machine/dynamics_parameters.hpp"
#include "machine/mechanism.hpp"

namespace pkm::dynamics {

/// What the pose fixes: the struts' ends, the actuator values, the twist Jacobian, the allowed twists, and
/// the platform with its payload as one body.
struct MechanismState {
  Pose pose;
  int struts = 0;
  StrutJointPoints ends;
  std::array<double, kMaxActuators> actuators{};
  std::array<Eigen::Vector3d, kMaxActuators> base_first;   ///< ∂A_j/∂q_j
  std::array<Eigen::Vector3d, kMaxActuators> base_second;  ///< ∂²A_j/∂q_j²
  std::array<bool, kMaxActuators> base_moves{};
  std::array<Eigen::Vector3d, kMaxActuators> strut_u;  ///< unit strut directions A_j → B_j
  std::array<double, kMaxActuators> strut_length_mm{};
  /// The same by rows over the struts (strut_rows.hpp), for the rigid terms' lanes: the platform joints from
  /// the tool point, the unit directions and 1/L, zero past `struts`.
  StrutRows3 strut_arm_rows_mm, strut_u_rows;
  StrutRow strut_inverse_length_per_mm = StrutRow::Zero();
  /// The struts' constants of the fixed-base terms, zero in the lanes of struts on moving base joints.
  FixedBaseStrutConstants fixed_base_constants;
  JacobianMatrix twist_jacobian;
  TwistBasis basis;
  double platform_kg = 0.0;
  Eigen::Vector3d platform_arm_mm = Eigen::Vector3d::Zero();          ///< tool point → CoM, base frame
  Eigen::Matrix3d platform_inertia_kg_mm2 = Eigen::Matrix3d::Zero();  ///< about the CoM, base frame
};

/// Fills `state` at a pose (completed first). Fails where the pose is out of reach or the mechanism gives no
/// twist form, or the dynamics parameters describe a different number of struts.
Status mechanism_state(const Mechanism& mechanism, const DynamicsParameters& parameters, const Pose& pose,
                       MechanismState& state);

/// From the state's pose and strut ends: each strut's length and unit direction (strut_length_mm, strut_u)
/// and the rows of the joints' arms, the directions and 1/L, computed over all struts at once (the same
/// operations per strut as d.norm() and d / L). Returns the first strut (from 0) of zero length, −1 when
/// every strut has a length. Never allocates.
int set_strut_directions(MechanismState& state);

/// state.fixed_base_constants: `constants` (fixed_base_strut_constants) with the lanes of the struts on
/// moving base joints (state.base_moves) zeroed.
void set_fixed_base_constants(const FixedBaseStrutConstants& constants, MechanismState& state);

/// A strut's motion: direction, its rate and angular velocity and acceleration (perpendicular to the axis).
struct StrutMotion {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_rate = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_accel = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();
};

/// Velocities (and, for a real motion, accelerations) of every body.
struct BodyMotion {
  int struts = 0;
  Eigen::Vector3d platform_v = Eigen::Vector3d::Zero(), platform_a = Eigen::Vector3d::Zero();  ///< CoM
  Eigen::Vector3d omega = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
  std::array<StrutMotion, kMaxActuators> strut;
  std::array<Eigen::Vector3d, kMaxActuators> lower_v, lower_a, upper_v, upper_a, base_v, base_a;
};

/// The bodies' motion for a platform twist (v, ω about the tool point) and its rate.
BodyMotion body_motion(const MechanismState& state, const DynamicsParameters& parameters,
                       const Eigen::Matrix<double, 6, 1>& twist,
                       const Eigen::Matrix<double, 6, 1>& twist_rate);
/// Velocities only (a virtual motion); the accelerations are left zero.
BodyMotion body_velocities(const MechanismState& state, const DynamicsParameters& parameters,
                           const Eigen::Matrix<double, 6, 1>& twist);

/// Rates of momentum of every body: m·a_c per body, and I·α + ω × I·ω about each CoM.
struct BodyMomentumRates {
  int struts = 0;
  Eigen::Vector3d platform_force = Eigen::Vector3d::Zero(), platform_moment = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, kMaxActuators> lower_force, upper_force, strut_moment, carriage_force;
};
BodyMomentumRates momentum_rates(const MechanismState& state, const DynamicsParameters& parameters,
                                 const BodyMotion& motion);

/// Σ (force · velocity + moment · angular velocity) of `rates` in the virtual motion `velocities`.
double power(const BodyMomentumRates& rates, const BodyMotion& velocities);
/// Σ m g · v_c of every body in `velocities`.
double gravity_power(const MechanismState& state, const DynamicsParameters& parameters,
                     const BodyMotion& velocities, const Eigen::Vector3d& gravity_mm_s2);
/// ½ Σ (m |v_c|² + ωᵀ I ω), kg·mm²/s².
double kinetic_energy(const MechanismState& state, const DynamicsParameters& parameters,
                      const BodyMotion& velocities);
/// −Σ m g · c, kg·mm²/s².
double gravity_potential(const MechanismState& state, const DynamicsParameters& parameters);

}  // namespace pkm::dynamics
