#include "dynamics/run_dynamics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/rotation.hpp"
#include "dynamics/drive_model.hpp"

namespace pkm::dynamics {

Status require_dynamics_section(const Machine& machine) {
  if (machine.dynamics.given()) return ok_status();
  return Error{ErrorCode::bad_input,
               fmt::format("{}: the machine file has no dynamics: section (masses and inertias, "
                           "docs/machine-file.md): the drive forces cannot be computed",
                           machine.source),
               ErrorLocation{machine.source, 0, 0, "dynamics"}};
}

RunDynamics::RunDynamics(const Machine& machine, double period_s,
                         std::function<Status(const TickDynamics&)> on_tick, const statics::LoadModel* load)
    : machine_(machine),
      period_s_(period_s),
      on_tick_(std::move(on_tick)),
      load_(load != nullptr && !load->empty() ? load : nullptr),
      tool_axis_platform_(machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ()) {
  summary_.drives = machine.mechanism->actuator_count();
}

Status RunDynamics::add(double time_s, int line, const Pose& pose, bool cutting) {
  const auto due = window_.add(Sample{time_s, line, pose, cutting});
  return due.index >= 0 ? evaluate(due.index, due.at_rest) : ok_status();
}

Status RunDynamics::finish() {
  if (const auto due = window_.finish(); due.index >= 0) {
    if (Status last = evaluate(due.index, due.at_rest); !last) return last;  // the end, at rest
  }
  return has_pending_ ? hand_on(nullptr) : ok_status();
}

Status RunDynamics::hand_on(const TickDynamics* next) {
  TickDynamics& tick = pending_;
  // Ṗ by the central difference of the forces either side, one-sided at the ends.
  const double before_s = has_handed_ ? handed_time_s_ : tick.time_s;
  const ActuatorVector& before_N = has_handed_ ? handed_force_N_ : tick.forces.total;
  const double after_s = next != nullptr ? next->time_s : tick.time_s;
  const ActuatorVector& after_N = next != nullptr ? next->forces.total : tick.forces.total;
  ActuatorVector force_rate_N_s = ActuatorVector::Zero(tick.forces.total.size());
  if (after_s > before_s) force_rate_N_s = (after_N - before_N) / (after_s - before_s);
  tick.command_N =
      command_for_force(machine_.dynamics, tick.forces.total, tick.forces.actuator_rates, force_rate_N_s);
  handed_time_s_ = tick.time_s;
  handed_force_N_ = tick.forces.total;
  has_handed_ = true;
  has_pending_ = false;
  if (on_tick_) return on_tick_(tick);
  return ok_status();
}

Status RunDynamics::evaluate(int index_in_window, bool at_rest) {
  const Sample& s = window_[index_in_window];
  PlatformMotion motion;
  motion.pose = s.pose;
  if (!at_rest) {
    // Central differences over the servo period: velocity and acceleration of the tool point, and the
    // rotation vectors of the two steps for the angular velocity and acceleration.
    const double h = period_s_;
    const Pose& before = window_[0].pose;
    const Pose& after = window_[2].pose;
    motion.velocity_mm_s = (after.position_mm - before.position_mm) / (2.0 * h);
    motion.acceleration_mm_s2 = (after.position_mm - 2.0 * s.pose.position_mm + before.position_mm) / (h * h);
    const Eigen::Vector3d step_in =
        rotation_vector_from_rotation(s.pose.rotation * before.rotation.transpose());
    const Eigen::Vector3d step_out =
        rotation_vector_from_rotation(after.rotation * s.pose.rotation.transpose());
    motion.angular_velocity_rad_s = (step_in + step_out) / (2.0 * h);
    motion.angular_acceleration_rad_s2 = (step_out - step_in) / (h * h);
  }
  statics::Wrench load;
  if (load_ != nullptr) {
    load = load_->wrench_at(
        statics::travel_load_point(s.pose, motion.velocity_mm_s, tool_axis_platform_, s.line, s.cutting));
  }
  auto forces = inverse_dynamics(*machine_.mechanism, machine_.dynamics, motion, load);
  if (!forces) {
    return Error{forces.error().code, fmt::format("at {:.3f} s: {}", s.time_s, forces.error().message),
                 ErrorLocation{"", s.line, 0, ""}};
  }
  TickDynamics tick;
  tick.time_s = s.time_s;
  tick.line = s.line;
  tick.forces = *forces;
  tick.power_W = forces->total.cwiseProduct(forces->actuator_rates) * 1e-3;  // N·mm/s → W

  const int n = summary_.drives;
  double total_power = 0.0;
  for (int j = 0; j < n; ++j) {
    const double force = std::abs(forces->total[j]);
    if (machine_.limits.force_N && force > *machine_.limits.force_N) {
      return Error{
          ErrorCode::limit_exceeded,
          fmt::format("at {:.3f} s: drive {} needs {:.1f} N, above actuator_force_max {:.1f} N ({}:{})",
                      s.time_s, j + 1, forces->total[j], *machine_.limits.force_N, machine_.source,
                      machine_.limits.force_line),
          ErrorLocation{"", s.line, 0, ""}};
    }
    if (force > summary_.peak_force_N[j]) {
      summary_.peak_force_N[j] = force;
      summary_.peak_force_time_s[j] = s.time_s;
      summary_.peak_force_line[j] = s.line;
    }
    summary_.peak_static_N[j] = std::max(summary_.peak_static_N[j], std::abs(forces->static_part[j]));
    summary_.peak_dynamic_N[j] = std::max(summary_.peak_dynamic_N[j], std::abs(forces->dynamic_part[j]));
    summary_.peak_power_W[j] = std::max(summary_.peak_power_W[j], std::abs(tick.power_W[j]));
    summary_.energy.no_recovery_J += std::abs(tick.power_W[j]) * period_s_;
    summary_.energy.braking_free_J += std::max(0.0, tick.power_W[j]) * period_s_;
    total_power += tick.power_W[j];
  }
  summary_.energy.recovery_J += std::max(0.0, total_power) * period_s_;
  if (std::abs(total_power) > summary_.peak_total_power_W) {
    summary_.peak_total_power_W = std::abs(total_power);
    summary_.peak_total_power_line = s.line;
  }
  ++summary_.ticks;
  if (has_pending_) {
    if (Status handed = hand_on(&tick); !handed) return handed;
  }
  pending_ = tick;
  has_pending_ = true;
  return ok_status();
}

}  // namespace pkm::dynamics
