#include "servo/loop_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pkm::servo {

ActuatorVector motor_inertia(const ServoParameters& parameters, int drives) {
  ActuatorVector out = ActuatorVector::Zero(drives);
  for (int j = 0; j < drives; ++j) {
    const DriveServo& d = parameters.drives[j];
    // kg·mm² · (rad/mm)² = kg = 10⁻³ N/(mm/s²); for angular actuators kg·mm² = 10⁻³ N·mm/(rad/s²).
    out[j] = 1e-3 * d.motor_inertia_kg_mm2 * d.motor_rad_per_unit * d.motor_rad_per_unit;
  }
  return out;
}

namespace {

Error servo_drive_error(const Machine& machine, int drive, int line, const char* key,
                        const std::string& what) {
  const std::string path = fmt::format("servo.drives[{}]{}{}", drive, *key ? "." : "", key);
  return Error{ErrorCode::bad_input, fmt::format("{}:{}: {}: {}", machine.source, line, path, what),
               ErrorLocation{machine.source, line, 0, path}};
}

}  // namespace

Result<LoopDesign> design_loops(const Machine& machine, const ActuatorVector& inertia) {
  const ServoParameters& parameters = machine.servo;
  LoopDesign design;
  design.tuning = parameters.tuning;
  design.drives = static_cast<int>(inertia.size());
  design.sample_delay_periods = parameters.sample_delay_periods;
  for (int j = 0; j < design.drives; ++j) {
    const DriveServo& d = parameters.drives[j];
    if (!(inertia[j] > 0.0) || !std::isfinite(inertia[j])) {
      return servo_drive_error(machine, j, d.line, "",
                               fmt::format("the drive moves no inertia ({}): give motor_inertia_kg_cm2 with "
                                           "its transmission, or a dynamics: section",
                                           inertia[j]));
    }
    if (!(d.current_time_constant_s > 0.0)) {
      return servo_drive_error(machine, j, d.time_constant_line, "current_time_constant_ms",
                               "must be positive");
    }
    ChannelGains& c = design.channels[j];
    const double t_mu = d.current_time_constant_s;
    c.lag_s = t_mu;
    c.force_per_command = d.current_gain * d.base_force;
    c.command_max = d.command_max * c.force_per_command;
    c.error_max = d.error_max;
    c.velocity_feedforward = parameters.velocity_feedforward;
    c.inertia = inertia[j];
    c.friction_coulomb = d.friction_coulomb;
    c.friction_static = std::max(d.friction_static, d.friction_coulomb);
    c.stribeck_speed = d.stribeck_speed;
    c.friction_viscous = d.friction_viscous;
    c.backlash = d.backlash;
    c.encoder_resolution = d.encoder_resolution;
    c.characteristic_points = d.characteristic_points;
    for (int k = 0; k < d.characteristic_points; ++k)
      c.characteristic[k] = {d.characteristic[k][0], d.characteristic[k][1] * d.base_force};
    switch (parameters.tuning) {
      case ServoTuning::technical_optimum:
        // K = T0/(2 k_μ T_μ) per unit, i.e. a/(2 T_μ) in force per speed (eq. 2.49's regulator).
        c.speed_gain = inertia[j] / (2.0 * t_mu);
        c.position_gain_per_s = 1.0 / (4.0 * t_mu);
        break;
      case ServoTuning::symmetric_optimum:
        c.speed_gain = inertia[j] / (2.0 * t_mu);
        c.speed_integral_s = 4.0 * t_mu;
        c.reference_filter_s = 4.0 * t_mu;
        c.position_gain_per_s = 1.0 / (8.0 * t_mu);
        break;
      case ServoTuning::explicit_gains:
        c.speed_gain = c.force_per_command * d.speed_gain / d.base_speed;
        c.speed_integral_s = d.speed_integral_s;
        c.position_gain_per_s = d.position_gain_per_s;
        break;
    }
  }
  return design;
}

}  // namespace pkm::servo
