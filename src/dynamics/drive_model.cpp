#include "dynamics/drive_model.hpp"

namespace pkm::dynamics {

void drive_response(const DynamicsParameters& parameters, const ActuatorVector& command_N,
                    const ActuatorVector& actuator_rates_mm_s, const ActuatorVector& lag_state_N,
                    DriveResponse& out) {
  out.force_rate_N_s.setZero(command_N.size());
  switch (parameters.drive) {
    case DriveModel::ideal:
      out.force_N = command_N;
      return;
    case DriveModel::static_characteristic:
      out.force_N = command_N - parameters.drive_speed_gain_N_s_mm * actuator_rates_mm_s;
      return;
    case DriveModel::first_order_lag:
      out.force_N = lag_state_N;
      out.force_rate_N_s = (command_N - lag_state_N) / parameters.drive_lag_s;
      return;
  }
}

ActuatorVector command_for_force(const DynamicsParameters& parameters, const ActuatorVector& force_N,
                                 const ActuatorVector& actuator_rates_mm_s,
                                 const ActuatorVector& force_rate_N_s) {
  switch (parameters.drive) {
    case DriveModel::ideal:
      return force_N;
    case DriveModel::static_characteristic:
      return force_N + parameters.drive_speed_gain_N_s_mm * actuator_rates_mm_s;
    case DriveModel::first_order_lag:
      return force_N + parameters.drive_lag_s * force_rate_N_s;
  }
  return force_N;
}

}  // namespace pkm::dynamics
