#pragma once
// The drive models of Smirnov 2019, §4.2: how a drive turns its command u_j into the force P_j it gives.
//   ideal                  P = u
//   static characteristic  P = u − k_v q̇        (the force falls with the speed; Smirnov gives no form)
//   first-order lag        τ Ṗ + P = u          (P becomes a state of the integration)
// The parameters are the machine file's `dynamics.drive` (machine/dynamics_parameters.hpp).
#include "machine/dynamics_parameters.hpp"

namespace pkm::dynamics {

/// The drive's force for its command, speed and, under a lag, its force state (Smirnov 2019, §4.2): the force
/// itself for ideal and static drives, the force's rate Ṗ = (u − P)/τ for the lag.
struct DriveResponse {
  ActuatorVector force_N;
  ActuatorVector force_rate_N_s;  ///< zero unless lagging
};
void drive_response(const DynamicsParameters& parameters, const ActuatorVector& command_N,
                    const ActuatorVector& actuator_rates_mm_s, const ActuatorVector& lag_state_N,
                    DriveResponse& out);

/// The drive command that makes the drive model give `force_N` while the actuators move at
/// `actuator_rates_mm_s` with the force changing at `force_rate_N_s`: the model's inverse, to pre-compensate
/// a feed-forward command (u = P + k_v q̇, or u = P + τ Ṗ).
ActuatorVector command_for_force(const DynamicsParameters& parameters, const ActuatorVector& force_N,
                                 const ActuatorVector& actuator_rates_mm_s,
                                 const ActuatorVector& force_rate_N_s);

}  // namespace pkm::dynamics
