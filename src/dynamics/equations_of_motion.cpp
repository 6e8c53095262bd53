#include "dynamics/equations_of_motion.hpp"

namespace pkm::dynamics {

bool platform_twist_basis(const Mechanism& mechanism, TwistBasis& basis) {
  const AxisMask mask = mechanism.controlled_axes();
  if (mask.count() == 6) {
    basis = TwistBasis::Identity(6, 6);
    return true;
  }
  if (mechanism.is_planar()) {
    basis = TwistBasis::Zero(6, 3);
    basis(0, 0) = 1.0;
    basis(1, 1) = 1.0;
    basis(5, 2) = 1.0;
    // A planar mechanism that does not control φ (the biped: a point) keeps x, y only.
    if (!mask.controlled[5]) basis.conservativeResize(6, 2);
    return true;
  }
  return false;
}

CoordinateForces coordinate_forces(const MechanismState& state, const DynamicsParameters& parameters,
                                   const TwistBasis& basis, const Twist& twist, const Twist& twist_rate,
                                   const statics::Wrench& load) {
  const int m = static_cast<int>(basis.cols());
  CoordinateForces q{ActuatorVector::Zero(m), ActuatorVector::Zero(m)};
  const BodyMomentumRates rates =
      momentum_rates(state, parameters, body_motion(state, parameters, twist, twist_rate));
  Twist wrench;
  wrench << load.force_N * 1e3, load.moment_Nmm * 1e3;  // N → kg·mm/s²
  for (int k = 0; k < m; ++k) {
    const BodyMotion virtual_motion = body_velocities(state, parameters, basis.col(k));
    q.dynamic[k] = power(rates, virtual_motion);
    q.applied[k] =
        gravity_power(state, parameters, virtual_motion, parameters.gravity_mm_s2) + wrench.dot(basis.col(k));
  }
  return q;
}

Result<EquationsOfMotion> equations_of_motion(const Mechanism& mechanism,
                                              const DynamicsParameters& parameters, const Pose& pose,
                                              const TwistBasis& basis, const Twist& twist,
                                              const statics::Wrench& load) {
  EquationsOfMotion e;
  if (Status s = mechanism_state(mechanism, parameters, pose, e.state); !s) return s.error();
  const int m = static_cast<int>(basis.cols());
  const CoordinateForces moving = coordinate_forces(e.state, parameters, basis, twist, Twist::Zero(), load);
  e.bias = moving.dynamic;
  e.applied = moving.applied;
  e.mass.resize(m, m);
  for (int k = 0; k < m; ++k) {
    // The dynamic forces are linear in the twist rate: at rest, a unit rate of coordinate k gives column k.
    e.mass.col(k) = coordinate_forces(e.state, parameters, basis, Twist::Zero(), basis.col(k), {}).dynamic;
  }
  e.drive_jacobian = e.state.twist_jacobian * basis;
  return e;
}

}  // namespace pkm::dynamics
