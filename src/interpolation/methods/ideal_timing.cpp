#include "interpolation/methods/ideal_timing.hpp"

#include <algorithm>
#include <cmath>

#include "planning/servo_stream.hpp"

namespace pkm::interpolation {

Result<IdealTiming> IdealTiming::from_plan(const planning::MotionPlan& plan, const Machine& machine) {
  IdealTiming timing;
  timing.period_s_ = plan.period_s;
  timing.length_ = plan.path.length();
  planning::ServoStream stream(plan, machine);
  timing.s_.reserve(static_cast<std::size_t>(stream.tick_count()));
  planning::ServoTick tick;
  while (stream.next(tick)) timing.s_.push_back(tick.s);
  if (stream.error()) return *stream.error();
  if (timing.s_.empty()) timing.s_.push_back(0.0);
  timing.s_.back() = timing.length_;
  timing.duration_s_ = static_cast<double>(timing.s_.size() - 1) * timing.period_s_;
  return timing;
}

IdealTiming IdealTiming::constant_speed(double length, double speed_per_s) {
  IdealTiming timing;
  timing.length_ = length;
  timing.speed_ = speed_per_s;
  timing.duration_s_ = speed_per_s > 0.0 ? length / speed_per_s : 0.0;
  return timing;
}

IdealTiming IdealTiming::window(double period_s) {
  IdealTiming timing;
  timing.period_s_ = period_s;
  timing.finished_ = false;
  timing.duration_s_ = std::numeric_limits<double>::infinity();
  return timing;
}

void IdealTiming::append(double s) {
  s_.push_back(s);
}

void IdealTiming::finish(double length) {
  length_ = length;
  if (base_ + s_.size() == 0) s_.push_back(0.0);
  s_.back() = length;
  duration_s_ = static_cast<double>(base_ + s_.size() - 1) * period_s_;
  finished_ = true;
}

void IdealTiming::drop_before(double tau_s) {
  if (!(tau_s > 0.0)) return;
  const auto tick = static_cast<std::size_t>(tau_s / period_s_);
  if (tick <= base_ + 1) return;
  // The tick before the interval containing τ stays too: s_at may round its index down by one.
  const std::size_t drop = std::min(tick - 1 - base_, s_.size() > 2 ? s_.size() - 2 : 0);
  if (drop == 0 || 2 * drop < s_.size()) return;
  s_.erase(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(drop));
  base_ += drop;
}

double IdealTiming::s_at(double tau_s) const noexcept {
  if (tau_s >= duration_s_) return length_;
  if (tau_s <= 0.0 && base_ == 0) return s_.empty() ? 0.0 : s_.front();
  if (s_.empty()) return std::min(length_, speed_ * tau_s);
  if (s_.size() < 2) return s_.front();
  const double k = tau_s / period_s_;
  const std::size_t tick = k > 0.0 ? static_cast<std::size_t>(k) : 0;
  const auto index = std::min(tick > base_ ? tick - base_ : 0, s_.size() - 2);
  const double f = k - static_cast<double>(base_ + index);
  return s_[index] + f * (s_[index + 1] - s_[index]);
}

double IdealTiming::speed_at(double tau_s) const noexcept {
  if (s_.empty()) return tau_s < duration_s_ ? speed_ : 0.0;
  if (s_.size() < 2 || tau_s < 0.0 || tau_s >= duration_s_) return 0.0;
  const auto tick = static_cast<std::size_t>(tau_s / period_s_);
  const auto index = std::min(tick > base_ ? tick - base_ : 0, s_.size() - 2);
  return (s_[index + 1] - s_[index]) / period_s_;
}

}  // namespace pkm::interpolation
