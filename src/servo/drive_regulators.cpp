#include "servo/drive_regulators.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::servo {

namespace {

// The force of a static characteristic for the command u: piecewise linear through the points (u rising
// from 0), odd in u, constant past the last point.
double characteristic_force(
    const std::array<std::array<double, 2>, DriveServo::kMaxCharacteristicPoints>& points, int count,
    double u) {
  const double magnitude = std::abs(u);
  double force = points[count - 1][1];
  for (int k = 1; k < count; ++k) {
    if (magnitude <= points[k][0]) {
      const double t = (magnitude - points[k - 1][0]) / (points[k][0] - points[k - 1][0]);
      force = points[k - 1][1] + t * (points[k][1] - points[k - 1][1]);
      break;
    }
  }
  return std::copysign(force, u);
}

}  // namespace

DriveRegulators::DriveRegulators(const LoopDesign& design, double loop_period_s)
    : drives_(design.drives), period_s_(loop_period_s) {
  for (DriveVector* v : {&position_gain_, &speed_gain_, &integral_gain_, &filter_keep_, &feedforward_,
                         &error_max_, &command_max_, &force_per_command_, &resolution_})
    v->setZero();
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
    resolution_[j] = c.encoder_resolution;
    encoder_ = encoder_ || resolution_[j] > 0.0;
    characteristic_[j] = c.characteristic;
    characteristic_points_[j] = c.characteristic_points;
  }
  delay_ = std::clamp(design.sample_delay_periods, 0, kMaxSampleDelay);
}

void DriveRegulators::reset(const DriveVector& position, const DriveVector& holding_force) {
  state_ = RegulatorState{};
  command_.setZero();
  for (int j = 0; j < kMaxActuators; ++j)
    counted_[j] = resolution_[j] > 0.0 ? std::round(position[j] / resolution_[j]) : position[j];
  for (int k = 0; k < kMaxSampleDelay; ++k) {
    state_.delayed_position[k] = position;
    state_.delayed_speed[k].setZero();
  }
  // The integral that holds the load without a speed error (symmetric optimum); P-only drives hold it with
  // a small speed error instead, reached within the first transient.
  for (int j = 0; j < kMaxActuators; ++j)
    state_.integral[j] = integral_gain_[j] > 0.0 ? holding_force[j] / integral_gain_[j] : 0.0;
  clamps_ = {};
}

// What the regulators see this period: the encoder's counts (and their difference as the speed) or the
// state itself, as sampled `delay_` periods ago.
void DriveRegulators::measure(const DriveVector& position, const DriveVector& speed,
                              DriveVector& measured_position, DriveVector& measured_speed) {
  DriveVector now_position = position, now_speed = speed;
  if (encoder_) {
    for (int j = 0; j < drives_; ++j) {
      if (!(resolution_[j] > 0.0)) continue;
      const double counts = std::round(position[j] / resolution_[j]);
      now_position[j] = counts * resolution_[j];
      now_speed[j] = (counts - counted_[j]) * resolution_[j] / period_s_;
      counted_[j] = counts;
    }
  }
  if (delay_ == 0) {
    measured_position = now_position;
    measured_speed = now_speed;
    return;
  }
  measured_position = state_.delayed_position[delay_ - 1];
  measured_speed = state_.delayed_speed[delay_ - 1];
  for (int k = delay_ - 1; k > 0; --k) {
    state_.delayed_position[k] = state_.delayed_position[k - 1];
    state_.delayed_speed[k] = state_.delayed_speed[k - 1];
  }
  state_.delayed_position[0] = now_position;
  state_.delayed_speed[0] = now_speed;
}

DriveVector DriveRegulators::regulate(const DriveVector& reference, const DriveVector& reference_speed,
                                      const DriveVector& position, const DriveVector& speed) {
  clamps_ = {};
  DriveVector measured_position, measured_speed;
  measure(position, speed, measured_position, measured_speed);
  DriveVector force_command = DriveVector::Zero();
  for (int j = 0; j < drives_; ++j) {
    double error = reference[j] - measured_position[j];
    if (std::abs(error) > error_max_[j]) {
      error = std::copysign(error_max_[j], error);
      clamps_.error |= 1u << j;
    }
    const double speed_reference = position_gain_[j] * error + feedforward_[j] * reference_speed[j];
    state_.filtered[j] = filter_keep_[j] * state_.filtered[j] + (1.0 - filter_keep_[j]) * speed_reference;
    const double speed_error = state_.filtered[j] - measured_speed[j];
    double command = speed_gain_[j] * speed_error + integral_gain_[j] * state_.integral[j];
    if (std::abs(command) > command_max_[j]) {
      command = std::copysign(command_max_[j], command);
      clamps_.command |= 1u << j;
    } else if (integral_gain_[j] > 0.0) {
      state_.integral[j] += speed_error * period_s_;  // no integration while limited (anti-windup)
    }
    command_[j] = command / force_per_command_[j];
    force_command[j] = characteristic_points_[j] > 1
                           ? characteristic_force(characteristic_[j], characteristic_points_[j], command_[j])
                           : command;
  }
  return force_command;
}

}  // namespace pkm::servo
