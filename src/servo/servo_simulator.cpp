#include "servo/servo_simulator.hpp"

#include <cmath>

namespace pkm::servo {

ServoSimulator::ServoSimulator(const LoopDesign& design, double loop_period_s)
    : drives_(design.drives), period_s_(loop_period_s), half_s_(0.5 * loop_period_s) {
  for (DriveVector* v :
       {&position_gain_, &speed_gain_, &integral_gain_, &filter_keep_, &feedforward_, &error_max_,
        &command_max_, &force_per_command_, &lag_keep_, &lag_first_, &lag_second_})
    v->setZero();
  const double h = half_s_;
  for (int j = 0; j < drives_; ++j) {
    const ChannelGains& c = design.channels[j];
    position_gain_[j] = c.position_gain_per_s;
    speed_gain_[j] = c.speed_gain;
    integral_gain_[j] = c.speed_integral_s > 0.0 ? c.speed_gain / c.speed_integral_s : 0.0;
    // The reference filter's exact discrete form for a reference held over the period.
    filter_keep_[j] = c.reference_filter_s > 0.0 ? std::exp(-period_s_ / c.reference_filter_s) : 0.0;
    feedforward_[j] = c.velocity_feedforward;
    error_max_[j] = c.error_max;
    command_max_[j] = c.command_max;
    force_per_command_[j] = c.force_per_command;
    // F(t) = F_cmd + (F0 − F_cmd) e^(−t/T_μ): ∫₀ʰ F = F_cmd h + (F0 − F_cmd) c1 with c1 = T_μ(1 − α), and
    // ∫₀ʰ∫₀ᵗ F = F_cmd h²/2 + (F0 − F_cmd) c2 with c2 = T_μ (h − c1).
    const double alpha = std::exp(-h / c.lag_s);
    lag_keep_[j] = alpha;
    lag_first_[j] = c.lag_s * (1.0 - alpha);
    lag_second_[j] = c.lag_s * (h - lag_first_[j]);
    inverse_inertia_(j, j) = 1.0 / c.inertia;
  }
}

void ServoSimulator::reset(const DriveVector& position) {
  position_ = position;
  speed_.setZero();
  force_ = load_;
  filtered_.setZero();
  command_.setZero();
  mid_position_ = position;
  // The integral that holds the load without a speed error (symmetric optimum); P-only drives hold it with
  // a small speed error instead, reached within the first transient.
  for (int j = 0; j < kMaxActuators; ++j)
    integral_[j] = integral_gain_[j] > 0.0 ? load_[j] / integral_gain_[j] : 0.0;
  clamps_ = {};
}

void ServoSimulator::advance_plant(const DriveVector& force_command) {
  const double h = half_s_;
  // Force impulse and its second integral of the lag over the half step, less the load's.
  const DriveVector change = force_ - force_command;
  const DriveVector impulse = force_command * h + change.cwiseProduct(lag_first_) - load_ * h;
  const DriveVector second =
      force_command * (0.5 * h * h) + change.cwiseProduct(lag_second_) - load_ * (0.5 * h * h);
  position_ += speed_ * h + inverse_inertia_ * second;
  speed_ += inverse_inertia_ * impulse;
  force_ = force_command + change.cwiseProduct(lag_keep_);
}

void ServoSimulator::step(const DriveVector& reference, const DriveVector& reference_speed) {
  clamps_ = {};
  DriveVector force_command = DriveVector::Zero();
  for (int j = 0; j < drives_; ++j) {
    double error = reference[j] - position_[j];
    if (std::abs(error) > error_max_[j]) {
      error = std::copysign(error_max_[j], error);
      clamps_.error |= 1u << j;
    }
    const double speed_reference = position_gain_[j] * error + feedforward_[j] * reference_speed[j];
    filtered_[j] = filter_keep_[j] * filtered_[j] + (1.0 - filter_keep_[j]) * speed_reference;
    const double speed_error = filtered_[j] - speed_[j];
    double command = speed_gain_[j] * speed_error + integral_gain_[j] * integral_[j];
    if (std::abs(command) > command_max_[j]) {
      command = std::copysign(command_max_[j], command);
      clamps_.command |= 1u << j;
    } else if (integral_gain_[j] > 0.0) {
      integral_[j] += speed_error * period_s_;  // no integration while limited (anti-windup)
    }
    force_command[j] = command;
    command_[j] = command / force_per_command_[j];
  }
  advance_plant(force_command);
  mid_position_ = position_;
  advance_plant(force_command);
}

ServoSimulator::StateVector ServoSimulator::state() const {
  StateVector out;
  out << position_, speed_, force_, integral_, filtered_;
  return out;
}

void ServoSimulator::set_state(const StateVector& state) {
  position_ = state.segment<kMaxActuators>(0);
  speed_ = state.segment<kMaxActuators>(kMaxActuators);
  force_ = state.segment<kMaxActuators>(2 * kMaxActuators);
  integral_ = state.segment<kMaxActuators>(3 * kMaxActuators);
  filtered_ = state.segment<kMaxActuators>(4 * kMaxActuators);
}

bool ServoSimulator::finite() const {
  return position_.allFinite() && speed_.allFinite() && force_.allFinite() && integral_.allFinite();
}

}  // namespace pkm::servo
