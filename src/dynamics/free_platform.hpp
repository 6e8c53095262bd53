#pragma once
// A mechanism whose platform moves freely in a fixed twist basis (platform_twist_basis: the six twist
// components, or (v_x, v_y, ω_z) for planar machines), with its dynamics parameters: what the time-domain
// models share. The elastic machine (elastic_model.hpp) puts springs in series with the drives; the rigid
// forward dynamics (rigid_simulation.hpp) drives the platform by the drives' forces.
#include <Eigen/Core>
#include <string>

#include "core/result.hpp"
#include "dynamics/body_motion.hpp"
#include "dynamics/equations_of_motion.hpp"
#include "machine/machine.hpp"

namespace pkm::dynamics {

/// The equations' force unit per newton: N → kg·mm/s².
inline constexpr double kKgMmS2PerN = 1e3;

/// Rates or accelerations of the basis coordinates (mm/s and rad/s, or their rates); at most six.
using CoordinateVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

/// The immutable part: the mechanism, its dynamics parameters and the platform's twist basis.
struct FreePlatformModel {
  const Mechanism* mechanism = nullptr;
  const DynamicsParameters* parameters = nullptr;
  TwistBasis basis;  ///< platform_twist_basis: the identity when there are six coordinates
  int coordinates = 0;
  int struts = 0;
  /// Every strut's base joint is fixed to the base (Mechanism::has_distance_actuators: each actuator is a
  /// distance from a base-fixed point), so base_joint_motion need not be asked at every evaluation.
  bool base_joints_fixed = false;
  /// The platform with its payload as one body (tool frame: centre of mass mm, inertia about it kg·mm²),
  /// combined once instead of at every evaluation.
  double platform_kg = 0.0;
  Eigen::Vector3d platform_com_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d platform_inertia_kg_mm2 = Eigen::Matrix3d::Zero();
  /// The struts' constants of the rigid terms on fixed base joints (strut_rows.hpp), likewise made once.
  FixedBaseStrutConstants strut_constants;
};

/// Fills `model` for `mechanism`, or says why it cannot have one: angular actuators, or no free twist basis
/// (tripod, tricept), or dynamics parameters for a different number of struts. `where` prefixes messages
/// (file:line: ), `purpose` names the model in them ("the elastic model").
Status make_free_platform_model(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                const std::string& where, const std::string& purpose,
                                FreePlatformModel& model);

/// What the right-hand sides need of the mechanism at a pose, through the interface: the completed pose, the
/// struts' ends, the actuator values, the base joints' motion, the twist Jacobian and the platform body
/// (mechanism_state less the controlled twists, which a fixed basis does not need). Never allocates on
/// success.
Status free_platform_state(const FreePlatformModel& model, const Pose& pose, MechanismState& state);

/// Solves M x = rhs for the model's mass matrix (the 6 × 6 by the fixed-size Cholesky, planar ones by
/// Eigen's); false where M is not positive definite. Never allocates.
bool solve_mass(const FreePlatformModel& model, const CoordinateMatrix& mass, const CoordinateVector& rhs,
                CoordinateVector& solution);

}  // namespace pkm::dynamics
