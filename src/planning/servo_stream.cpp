#include "planning/servo_stream.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "planning/path_sampling.hpp"
#include "planning/plan_producer.hpp"

namespace pkm::planning {

ServoStream::ServoStream(const MotionPlan& plan, const Machine& machine, PlanProducer* source)
    : plan_(plan),
      machine_(machine),
      source_(source),
      cursor_(plan.samples, plan.timed),
      ring_(static_cast<std::size_t>(plan.filter_ticks), 0.0) {
  if (source == nullptr || source->finished()) last_tick_ = std::lround(plan.duration_s / plan.period_s);
}

bool ServoStream::next(ServoTick& tick) {
  if (k_ > last_tick_ || error_) return false;
  const int n = plan_.filter_ticks;
  const double t = static_cast<double>(k_) * plan_.period_s;
  if (source_ != nullptr) {
    // What the ticks passed goes (the mid-period point is still searched from the tick before's segment);
    // then the plan reaches past this tick, or to its end, which fixes the last tick.
    source_->release(cursor_.index(), std::min(hint_, hold_segment_));
    if (Status planned = source_->extend_to(t); !planned) {
      error_ = planned.error();
      return false;
    }
    if (last_tick_ == kUnknownEnd && source_->finished()) {
      last_tick_ = std::lround(plan_.duration_s / plan_.period_s);
      if (k_ > last_tick_) return false;
    }
  }
  const double raw = cursor_.position_at(t);
  const std::size_t slot = static_cast<std::size_t>(k_ % n);
  sum_ += raw - ring_[slot];
  ring_[slot] = raw;
  if (slot == static_cast<std::size_t>(n - 1)) {  // re-add now and then so rounding cannot drift
    sum_ = 0.0;
    for (double v : ring_) sum_ += v;
  }
  // The last tick is where every value in the window is the end: exactly the end of the path.
  double s = k_ == last_tick_ ? plan_.path.length() : sum_ / n;
  s = std::max(s, previous_s_);  // monotone even under rounding
  tick.has_mid_point = mid_points_ && k_ > 0;
  if (tick.has_mid_point) {
    int mid_hint = hint_;  // the segment of the tick before, as the monitor would search from
    tick.mid_point = plan_.path.evaluate(0.5 * (s + previous_s_), mid_hint);
  }
  const path::PathPoint point = plan_.path.evaluate(s, hint_);
  tick.index = k_;
  tick.time_s = t;
  tick.path_speed = k_ == 0 ? 0.0 : (s - previous_s_) / plan_.period_s;
  tick.s = s;
  tick.segment = hint_;
  tick.on_segment = plan_.path.segments.empty() ? path::Segment{} : plan_.path.segment(hint_);
  tick.line = tick.on_segment.line;
  tick.pose = Pose{point.position_mm, point.rotation.toRotationMatrix()};
  auto ik = machine_.mechanism->inverse(tick.pose);
  if (!ik) {
    error_ = Error{ErrorCode::unreachable,
                   fmt::format("{}:{}: the path leaves the workspace at {}: {}", plan_.program_source,
                               tick.line, program_pose_text(machine_, tick.pose), ik.error().message)};
    return false;
  }
  tick.actuators = *ik;
  if (Status status = check_actuator_range(machine_, tick.actuators); !status) {
    error_ = Error{status.error().code,
                   fmt::format("{}:{}: {}", plan_.program_source, tick.line, status.error().message)};
    return false;
  }
  previous_s_ = s;
  ++k_;
  return true;
}

}  // namespace pkm::planning
