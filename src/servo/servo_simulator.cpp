#include "servo/servo_simulator.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::servo {

namespace {

// Sub-steps of each half period in which friction is held (it changes with the speed within the period).
constexpr int kFrictionSubsteps = 8;
// Below this speed a drive under friction counts as at rest (mm/s or rad/s): where the zero-crossing clamp
// leaves it.
constexpr double kRestSpeed = 1e-12;

}  // namespace

ServoSimulator::LagStep ServoSimulator::lag_step(const LoopDesign& design, double duration_s) {
  LagStep step;
  step.duration_s = duration_s;
  for (int j = 0; j < design.drives; ++j) {
    // F(t) = F_cmd + (F0 − F_cmd) e^(−t/T_μ): ∫₀ʰ F = F_cmd h + (F0 − F_cmd) c1 with c1 = T_μ(1 − α), and
    // ∫₀ʰ∫₀ᵗ F = F_cmd h²/2 + (F0 − F_cmd) c2 with c2 = T_μ (h − c1).
    const double lag = design.channels[j].lag_s;
    const double alpha = std::exp(-duration_s / lag);
    step.keep[j] = alpha;
    step.first[j] = lag * (1.0 - alpha);
    step.second[j] = lag * (duration_s - step.first[j]);
  }
  return step;
}

ServoSimulator::ServoSimulator(const LoopDesign& design, double loop_period_s)
    : drives_(design.drives),
      period_s_(loop_period_s),
      half_s_(0.5 * loop_period_s),
      regulators_(design, loop_period_s) {
  for (DriveVector* v : {&coulomb_, &static_friction_, &stribeck_, &viscous_, &backlash_}) v->setZero();
  for (int j = 0; j < drives_; ++j) {
    const ChannelGains& c = design.channels[j];
    inverse_inertia_(j, j) = 1.0 / c.inertia;
    coulomb_[j] = c.friction_coulomb;
    static_friction_[j] = std::max(c.friction_static, c.friction_coulomb);
    stribeck_[j] = c.stribeck_speed;
    viscous_[j] = c.friction_viscous;
    backlash_[j] = c.backlash;
    friction_ = friction_ || static_friction_[j] > 0.0 || viscous_[j] > 0.0;
    backlash_on_ = backlash_on_ || backlash_[j] > 0.0;
  }
  half_step_ = lag_step(design, half_s_);
  sub_step_ = lag_step(design, half_s_ / kFrictionSubsteps);
}

void ServoSimulator::reset(const DriveVector& position) {
  position_ = position;
  actuator_ = mid_actuator_ = position;  // the backlash's gap centred
  speed_.setZero();
  force_ = load_;
  mid_position_ = position;
  regulators_.reset(position, load_);
}

void ServoSimulator::advance(const DriveVector& force_command, const DriveVector& load, const LagStep& step) {
  const double h = step.duration_s;
  // Force impulse and its second integral of the lag over the step, less the load's.
  const DriveVector change = force_ - force_command;
  const DriveVector impulse = force_command * h + change.cwiseProduct(step.first) - load * h;
  const DriveVector second =
      force_command * (0.5 * h * h) + change.cwiseProduct(step.second) - load * (0.5 * h * h);
  position_ += speed_ * h + inverse_inertia_ * second;
  speed_ += inverse_inertia_ * impulse;
  force_ = force_command + change.cwiseProduct(step.keep);
}

void ServoSimulator::advance_plant(const DriveVector& force_command) {
  if (friction_) {
    advance_with_friction(force_command);
  } else {
    advance(force_command, load_, half_step_);
  }
}

// The friction force on each drive at `speed` (Stribeck curve plus viscous), or, for a drive at rest, the
// force that keeps it there as long as the net force on it is within the static friction (its bit in
// `stuck`); a drive at rest pushed harder breaks away against F_s.
DriveVector ServoSimulator::friction_on(const DriveVector& speed, const DriveVector& net_force,
                                        std::uint32_t& stuck) const {
  DriveVector friction = DriveVector::Zero();
  stuck = 0;
  for (int j = 0; j < drives_; ++j) {
    const double w = speed[j];
    if (std::abs(w) <= kRestSpeed) {
      if (std::abs(net_force[j]) <= static_friction_[j]) {
        friction[j] = net_force[j];
        stuck |= 1u << j;
      } else {
        friction[j] = std::copysign(static_friction_[j], net_force[j]);
      }
      continue;
    }
    const double ratio = stribeck_[j] > 0.0 ? w / stribeck_[j] : 0.0;
    const double dry = stribeck_[j] > 0.0
                           ? coulomb_[j] + (static_friction_[j] - coulomb_[j]) * std::exp(-ratio * ratio)
                           : coulomb_[j];
    friction[j] = std::copysign(dry, w) + viscous_[j] * w;
  }
  return friction;
}

void ServoSimulator::advance_with_friction(const DriveVector& force_command) {
  for (int k = 0; k < kFrictionSubsteps; ++k) {
    std::uint32_t stuck = 0;
    const DriveVector friction = friction_on(speed_, force_ - load_, stuck);
    const DriveVector before_position = position_, before_speed = speed_;
    advance(force_command, load_ + friction, sub_step_);
    for (int j = 0; j < drives_; ++j) {
      // A drive held by static friction stays; one whose speed friction would reverse stops (it then sticks
      // or breaks away at the next sub-step).
      const bool reversed = before_speed[j] != 0.0 && before_speed[j] * speed_[j] < 0.0 &&
                            std::abs(friction[j]) > 0.0 && friction[j] * before_speed[j] > 0.0;
      if ((stuck & (1u << j)) != 0) {
        position_[j] = before_position[j];
        speed_[j] = 0.0;
      } else if (reversed) {
        speed_[j] = 0.0;
      }
    }
  }
}

// The actuator follows the motor through its gap: it moves only when the motor pushes on one side.
void ServoSimulator::take_up_backlash(DriveVector& actuator) const {
  for (int j = 0; j < drives_; ++j) {
    const double half = 0.5 * backlash_[j];
    actuator[j] = std::clamp(actuator[j], position_[j] - half, position_[j] + half);
  }
}

void ServoSimulator::step(const DriveVector& reference, const DriveVector& reference_speed) {
  const DriveVector force_command = regulators_.regulate(reference, reference_speed, position_, speed_);
  advance_plant(force_command);
  mid_position_ = position_;
  if (backlash_on_) take_up_backlash(actuator_);
  mid_actuator_ = backlash_on_ ? actuator_ : position_;
  advance_plant(force_command);
  if (backlash_on_) {
    take_up_backlash(actuator_);
  } else {
    actuator_ = position_;
  }
}

ServoSimulator::StateVector ServoSimulator::state() const {
  StateVector out;
  const RegulatorState& r = regulators_.state();
  out.head<5 * kMaxActuators>() << position_, speed_, force_, r.integral, r.filtered;
  for (int k = 0; k < kMaxSampleDelay; ++k) {
    out.segment<kMaxActuators>(kDelayedPositionState + k * kMaxActuators) = r.delayed_position[k];
    out.segment<kMaxActuators>(kDelayedSpeedState + k * kMaxActuators) = r.delayed_speed[k];
  }
  return out;
}

void ServoSimulator::set_state(const StateVector& state) {
  position_ = state.segment<kMaxActuators>(0);
  speed_ = state.segment<kMaxActuators>(kMaxActuators);
  force_ = state.segment<kMaxActuators>(2 * kMaxActuators);
  RegulatorState& r = regulators_.state();
  r.integral = state.segment<kMaxActuators>(3 * kMaxActuators);
  r.filtered = state.segment<kMaxActuators>(4 * kMaxActuators);
  for (int k = 0; k < kMaxSampleDelay; ++k) {
    r.delayed_position[k] = state.segment<kMaxActuators>(kDelayedPositionState + k * kMaxActuators);
    r.delayed_speed[k] = state.segment<kMaxActuators>(kDelayedSpeedState + k * kMaxActuators);
  }
  actuator_ = mid_actuator_ = position_;
}

bool ServoSimulator::finite() const {
  return position_.allFinite() && speed_.allFinite() && force_.allFinite() && regulators_.finite();
}

}  // namespace pkm::servo
