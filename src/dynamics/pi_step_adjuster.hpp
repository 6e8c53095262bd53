#pragma once
// A proportional–integral step-size controller for Boost.Odeint's controlled Runge–Kutta steppers (its
// StepAdjuster concept), in place of Odeint's default, which only keeps or grows the step after an accepted
// one (grows it only below half the tolerance) and shrinks it after a rejected one.
//
// Why: the elastic machine's step is held by its fastest vibration (docs/PERFORMANCE.md, elastic
// simulation): near the edge of Dormand–Prince's stability region the error grows from step to step, and the
// plain controller answers with a rejection, a cut and a slow regrowth, one step in ten. Gustafsson's PI
// control (Hairer & Wanner, Solving ODEs II, §IV.2, eq. 2.43c; the constants of their DOPRI5 code: safety
// 0.9, β = 0.04, exponent 1/5 − 0.75 β, factors within [0.2, 10], no growth right after a rejection) weighs
// the last accepted error against the present one and holds the step steady there.
#include <algorithm>
#include <cmath>

namespace pkm::dynamics {

template <class Value, class Time>
class PiStepAdjuster {
 public:
  using value_type = Value;
  using time_type = Time;

  /// `max_dt` 0: no limit on the step.
  explicit PiStepAdjuster(Time max_dt = Time{0}) : max_dt_(max_dt) {}

  /// After a rejected step (error > 1, in units of the tolerance).
  Time decrease_step(Time dt, Value error, int /*error_order*/) {
    rejected_ = true;
    return limited(dt * std::max(kMinFactor, kSafety * std::pow(error, -kAlpha)));
  }

  /// After an accepted step (error ≤ 1).
  Time increase_step(Time dt, Value error, int /*stepper_order*/) {
    error = std::max(error, kSmallestError);
    const Value factor = kSafety * std::pow(error, -kAlpha) * std::pow(previous_error_, kBeta);
    const Value most = rejected_ ? Value{1} : kMaxFactor;
    previous_error_ = error;
    rejected_ = false;
    return limited(dt * std::clamp(factor, kMinFactor, most));
  }

  bool check_step_size_limit(Time dt) const {
    return max_dt_ == Time{0} || std::abs(dt) <= std::abs(max_dt_);
  }
  Time get_max_dt() const { return max_dt_; }

 private:
  static constexpr Value kSafety = 0.9;
  static constexpr Value kBeta = 0.04;
  static constexpr Value kAlpha = 0.2 - 0.75 * kBeta;
  static constexpr Value kMinFactor = 0.2, kMaxFactor = 10.0;
  static constexpr Value kSmallestError = 1e-4;  // also the "last error" before the first step

  Time limited(Time dt) const {
    return max_dt_ != Time{0} && std::abs(dt) > std::abs(max_dt_) ? std::copysign(std::abs(max_dt_), dt) : dt;
  }

  Time max_dt_;
  Value previous_error_ = kSmallestError;
  bool rejected_ = false;
};

}  // namespace pkm::dynamics
