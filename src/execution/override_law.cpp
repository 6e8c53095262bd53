#include "execution/override_law.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::execution {

OverrideLaw::OverrideLaw(const OverrideRates& rates, double period_s, double initial_factor)
    : rates_(rates), period_s_(period_s), factor_(initial_factor) {}

void OverrideLaw::reset(double factor) noexcept {
  factor_ = factor;
  rate_per_s_ = 0.0;
}

namespace {

// How far K still moves at rate v ≥ 0 when every later period decelerates at a_max, the last one just to
// rest (the law can only change K̈ at period boundaries).
double discrete_stopping_distance(double v, double a_max, double h) {
  if (v <= 0.0) return 0.0;
  const double full_periods = std::floor(v / (a_max * h));
  const double t = full_periods * h;
  const double remaining = v - a_max * t;
  return v * t - 0.5 * a_max * t * t + 0.5 * remaining * h;
}

}  // namespace

double OverrideLaw::advance(double target) noexcept {
  if (settled_at(target)) return factor_;  // the usual period: nothing to change (K = 1 stays exactly 1)
  const double h = period_s_;
  const double a_max = rates_.max_accel_per_s2, v_max = rates_.max_rate_per_s;
  // In the frame where the target lies ahead (distance ≥ 0), K̈ is the largest in [−a_max, a_max] (and K̇
  // within ±v_max) from which K can still come to rest at the target; bisection, as the condition is
  // monotone in K̈.
  const double sign = target >= factor_ ? 1.0 : -1.0;
  const double distance = sign * (target - factor_);
  const double v = sign * rate_per_s_;
  auto can_stop = [&](double u) {
    const double v_next = v + u * h;
    const double left = distance - (v * h + 0.5 * u * h * h);
    return v_next <= 0.0 ? left >= -1e-15 : discrete_stopping_distance(v_next, a_max, h) <= left;
  };
  double low = std::max(-a_max, (-v_max - v) / h), high = std::min(a_max, (v_max - v) / h);
  double u = low;
  if (can_stop(high)) {
    u = high;
  } else if (can_stop(low)) {
    for (int i = 0; i < 60; ++i) {
      const double middle = 0.5 * (low + high);
      (can_stop(middle) ? low : high) = middle;
    }
    u = low;
  }
  const double advance_periods = factor_ + sign * (0.5 * v * h + u * h * h / 6.0);
  factor_ += sign * (v * h + 0.5 * u * h * h);
  rate_per_s_ = sign * (v + u * h);
  // At the target to rounding: settle on it exactly (K = 1 is then exactly 1).
  if (std::abs(target - factor_) <= 1e-12 && std::abs(rate_per_s_) <= 1e-6 * a_max * h) {
    factor_ = target;
    rate_per_s_ = 0.0;
  }
  return std::max(advance_periods, 0.0);
}

}  // namespace pkm::execution
