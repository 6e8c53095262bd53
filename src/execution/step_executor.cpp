#include "execution/step_executor.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::execution {

namespace {

// The interpolant's value between p1 and p2 at fraction f, from the points around them (Catmull–Rom: the
// cubic with the central differences as slopes, C¹ across points, exact for quadratics).
double catmull_rom(double p0, double p1, double p2, double p3, double f) {
  return p1 + f * (0.5 * (p2 - p0) +
                   f * ((p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3) + f * (0.5 * (p3 - p0) + 1.5 * (p1 - p2))));
}

}  // namespace

StepExecutor::StepExecutor(const ExecutorSettings& settings)
    : settings_(settings), law_(settings.rates, settings.period_s, 1.0) {}

void StepExecutor::start(const StepArray& start_steps) {
  first_ = 0;
  count_ = 1;
  base_ = 0;
  fraction_ = 0.0;
  stream_ended_ = false;
  limit_point_ = -1;
  fault_line_ = 0;
  NominalPeriod& origin = ring_[0];
  for (int j = 0; j < kMaxActuators; ++j) origin.ideal_steps[j] = static_cast<double>(start_steps[j]);
  origin.position_steps = start_steps;
  origin.line = 0;
  released_ = start_steps;
  law_.reset(1.0);  // the motion starts at rest: K may take the operator's value at once
  state_ = ExecutionState::running;
}

const NominalPeriod& StepExecutor::point(long index) const noexcept {
  return ring_[static_cast<std::size_t>(index % static_cast<long>(ring_.size()))];
}

bool StepExecutor::has_room() const noexcept {
  return count_ < static_cast<long>(ring_.size()) && !stream_ended_ && limit_point_ < 0;
}

bool StepExecutor::inside_stops(const StepArray& position) const noexcept {
  for (int j = 0; j < settings_.drives; ++j) {
    if (position[j] < settings_.min_position_steps[j] || position[j] > settings_.max_position_steps[j])
      return false;
  }
  return true;
}

bool StepExecutor::push(const NominalPeriod& period) noexcept {
  if (!has_room()) return false;
  const long index = first_ + count_;
  ring_[static_cast<std::size_t>(index % static_cast<long>(ring_.size()))] = period;
  ++count_;
  if (!inside_stops(period.position_steps)) {
    limit_point_ = index;  // never released: the motion stops before the period that leaves the range
    fault_line_ = period.line;
    return false;
  }
  return true;
}

long StepExecutor::periods_ahead() const noexcept {
  const long last_safe = limit_point_ >= 0 ? limit_point_ - 1 : first_ + count_ - 1;
  return last_safe - base_;
}

double StepExecutor::stopping_distance_periods() const noexcept {
  // From K and K̇: at most the time to turn K̇ round, then to fall at the largest rate, at the highest K on
  // the way (the law's braking curve is never slower than this).
  const double k = law_.factor(), rate = law_.rate_per_s();
  const double a_max = settings_.rates.max_accel_per_s2, v_max = settings_.rates.max_rate_per_s;
  const double rising = rate > 0.0 ? rate / a_max : 0.0;
  const double peak = k + (rate > 0.0 ? rate * rate / (2.0 * a_max) : 0.0);
  const double time_s = rising + peak / v_max + v_max / a_max;
  return peak * time_s / settings_.period_s + 2.0;
}

void StepExecutor::interpolate(ExecutedPeriod& out) const noexcept {
  const long last_safe = base_ + std::max(0L, periods_ahead());
  const NominalPeriod& at = point(base_);
  if (fraction_ == 0.0) {  // on the nominal grid: the nominal whole steps themselves
    out.position_steps = at.position_steps;
    out.set_point_steps = at.ideal_steps;
    out.line = at.line;
    return;
  }
  const NominalPeriod& before = point(std::max(base_ - 1, first_));
  const NominalPeriod& next = point(std::min(base_ + 1, last_safe));
  const NominalPeriod& after = point(std::min(base_ + 2, last_safe));
  for (int j = 0; j < settings_.drives; ++j) {
    const double value = catmull_rom(before.ideal_steps[j], at.ideal_steps[j], next.ideal_steps[j],
                                     after.ideal_steps[j], fraction_);
    out.set_point_steps[j] = value;
    out.position_steps[j] = std::llround(value);
  }
  out.line = next.line;
}

void StepExecutor::period(const ExecutionControls& controls, ExecutedPeriod& out) noexcept {
  out.steps.fill(0);
  if (state_ != ExecutionState::running && state_ != ExecutionState::starved) {
    out.position_steps = released_;
    for (int j = 0; j < kMaxActuators; ++j) out.set_point_steps[j] = static_cast<double>(released_[j]);
    out.factor = 0.0;
    out.tau_periods = static_cast<double>(base_) + fraction_;
    out.state = state_;
    out.line = state_ == ExecutionState::idle ? 0 : point(base_).line;
    return;
  }
  const double tau = static_cast<double>(base_) + fraction_;
  const long ahead = periods_ahead();
  const bool at_end = stream_ended_ && limit_point_ < 0;
  double target = std::clamp(controls.override_factor, 0.0, settings_.max_override);
  if (controls.hold || controls.abort) target = 0.0;
  // Not enough motion ahead to stop in, before the end of what has streamed in or before a software stop:
  // slow down now (the stream catches up, or the motion stops in time).
  const bool short_of_periods = !at_end && static_cast<double>(ahead) < stopping_distance_periods();
  if (short_of_periods && base_ == 0 && fraction_ == 0.0) {
    // Not begun: the drives wait at the start, K unchanged, until the stream is far enough ahead, so that a
    // program that streams in fast enough is executed as planned from its first period. A software stop
    // closer than the motion needs to stop refuses the program before it moves.
    interpolate(out);
    out.steps.fill(0);
    out.factor = law_.factor();
    out.tau_periods = 0.0;
    out.state = state_ = controls.abort      ? ExecutionState::aborted
                         : limit_point_ >= 0 ? ExecutionState::stopped_at_limit
                                             : ExecutionState::starved;
    if (controls.abort) stream_ended_ = true;  // nothing moved: the whole program is dropped
    return;
  }
  if (short_of_periods) target = 0.0;

  // τ never passes the last point it may reach: the end of the program (where the nominal motion is at
  // rest), or the last period before a software stop or the end of what has streamed in.
  const double cap = static_cast<double>(base_ + std::max(0L, ahead));
  double advance = law_.advance(target);
  if (tau + advance >= cap) {
    advance = std::max(0.0, cap - tau);
    if (!at_end) law_.reset(0.0);  // only by a fault of the stopping distance: hold where the motion is
  }
  fraction_ += advance;
  if (tau + advance >= cap) base_ = static_cast<long>(cap), fraction_ = 0.0;
  while (fraction_ >= 1.0) ++base_, fraction_ -= 1.0;
  while (first_ < base_ - 1) ++first_, --count_;  // points behind τ are no longer needed

  interpolate(out);
  for (int j = 0; j < settings_.drives; ++j) {
    out.steps[j] = out.position_steps[j] - released_[j];
  }
  released_ = out.position_steps;
  out.factor = law_.factor();
  out.tau_periods = static_cast<double>(base_) + fraction_;

  const bool stopped = law_.settled_at(0.0);
  if (at_end && fraction_ == 0.0 && base_ == first_ + count_ - 1) {
    state_ = ExecutionState::finished;
  } else if (controls.abort && stopped) {
    state_ = ExecutionState::aborted;  // the rest of the program is dropped
    stream_ended_ = true;
    count_ = base_ - first_ + 1 + (fraction_ > 0.0 ? 1 : 0);
  } else if (limit_point_ >= 0 && stopped && short_of_periods) {
    state_ = ExecutionState::stopped_at_limit;
  } else {
    state_ = short_of_periods && limit_point_ < 0 ? ExecutionState::starved : ExecutionState::running;
  }
  out.state = state_;
}

}  // namespace pkm::execution
