#include "dynamics/rigid_dynamics.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "dynamics/equations_of_motion.hpp"

namespace pkm::dynamics {
namespace {

constexpr double kNewtonsPerKgMmS2 = 1e-3;  // kg·mm/s² → N
constexpr double kJoulesPerKgMm2S2 = 1e-6;  // kg·mm²/s² → J
/// Smallest/largest pivot of the column-equilibrated J_cᵀ below which the drives cannot hold the platform
/// (as statics' kSingularPivotRatio).
constexpr double kSingularPivotRatio = 1e-9;

}  // namespace

Result<DriveForces> inverse_dynamics(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                     const PlatformMotion& motion, const statics::Wrench& load) {
  MechanismState state;
  if (Status s = mechanism_state(mechanism, parameters, motion.pose, state); !s) return s.error();
  const int n = mechanism.actuator_count();
  const int m = static_cast<int>(state.basis.cols());
  if (n != m) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("dynamics: {} actuators for {} controlled coordinates; the forces are not "
                                  "determined by the motion alone",
                                  n, m));
  }
  Eigen::Matrix<double, 6, 1> twist, twist_rate;
  twist << motion.velocity_mm_s, motion.angular_velocity_rad_s;
  twist_rate << motion.acceleration_mm_s2, motion.angular_acceleration_rad_s2;
  const CoordinateForces q = coordinate_forces(state, parameters, state.basis, twist, twist_rate, load);

  // J_cᵀ P = Q_dynamic − Q_applied, columns equilibrated so that the singularity test does not depend on
  // units.
  CoordinateMatrix jc = state.twist_jacobian * state.basis;
  ActuatorVector column_norm(m);
  for (int c = 0; c < m; ++c) {
    column_norm[c] = jc.col(c).norm();
    if (!(column_norm[c] > 0.0)) {
      return make_error(ErrorCode::singular,
                        "dynamics: the Jacobian is singular here (a coordinate moves no drive)");
    }
    jc.col(c) /= column_norm[c];
  }
  const Eigen::FullPivLU<CoordinateMatrix> lu(jc.transpose());
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  if (!(pivots.minCoeff() > kSingularPivotRatio * pivots.maxCoeff())) {
    return make_error(ErrorCode::singular,
                      "dynamics: the Jacobian is singular here; the drives cannot hold the platform");
  }
  DriveForces forces;
  const ActuatorVector dynamic_rhs = q.dynamic.cwiseQuotient(column_norm);
  const ActuatorVector static_rhs = (-q.applied).cwiseQuotient(column_norm);
  forces.dynamic_part = lu.solve(dynamic_rhs) * kNewtonsPerKgMmS2;
  forces.static_part = lu.solve(static_rhs) * kNewtonsPerKgMmS2;
  forces.total = forces.static_part + forces.dynamic_part;
  forces.actuator_rates = state.twist_jacobian * twist;
  return forces;
}

Result<double> kinetic_energy_J(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                const PlatformMotion& motion) {
  MechanismState state;
  if (Status s = mechanism_state(mechanism, parameters, motion.pose, state); !s) return s.error();
  Eigen::Matrix<double, 6, 1> twist;
  twist << motion.velocity_mm_s, motion.angular_velocity_rad_s;
  return kinetic_energy(state, parameters, body_velocities(state, parameters, twist)) * kJoulesPerKgMm2S2;
}

Result<double> gravity_potential_J(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                   const Pose& pose) {
  MechanismState state;
  if (Status s = mechanism_state(mechanism, parameters, pose, state); !s) return s.error();
  return gravity_potential(state, parameters) * kJoulesPerKgMm2S2;
}

}  // namespace pkm::dynamics
