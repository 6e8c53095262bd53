#include "planning/run_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/units.hpp"
#include "planning/path_sampling.hpp"

namespace pkm::planning {

RunMonitor::RunMonitor(const MotionPlan& plan, const Machine& machine, double override_pct,
                       bool evaluate_path_error)
    : plan_(plan),
      machine_(machine),
      override_factor_(override_pct / 100.0),
      evaluate_error_(evaluate_path_error) {
  summary_.rate_hz = 1.0 / plan.period_s;
  summary_.override_pct = override_pct;
  summary_.path_error_evaluated = evaluate_path_error;
  summary_.min_position.fill(std::numeric_limits<double>::infinity());
  summary_.max_position.fill(-std::numeric_limits<double>::infinity());
  fk_guess_ = machine.mechanism->home();
  if (evaluate_path_error) fk_workspace_ = machine.mechanism->make_fk_workspace();
  previous_velocity_ = ActuatorVector::Zero(machine.mechanism->actuator_count());
  last_accel_ = ActuatorVector::Zero(machine.mechanism->actuator_count());
}

void RunMonitor::add(const ServoTick& tick) {
  const double h = plan_.period_s;
  const int n = static_cast<int>(tick.actuators.size());
  last_path_error_mm_ = std::numeric_limits<double>::quiet_NaN();
  last_orientation_ = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  last_fk_failed_ = false;
  last_feed_ratio_ = 0.0;
  last_feed_cap_ = segment_speed_cap(tick.on_segment, machine_.motion, override_factor_);
  for (int j = 0; j < n; ++j) {
    summary_.min_position[j] = std::min(summary_.min_position[j], tick.actuators[j]);
    summary_.max_position[j] = std::max(summary_.max_position[j], tick.actuators[j]);
  }
  if (count_ > 0) {
    const ActuatorVector velocity = (tick.actuators - previous_.actuators) / h;
    for (int j = 0; j < n; ++j) {
      const double speed = std::abs(velocity[j]);
      if (speed > summary_.max_speed[j]) summary_.max_speed[j] = speed;
      if (speed > summary_.max_actuator_speed)
        summary_.max_actuator_speed = speed, summary_.max_speed_line = tick.line;
      const int direction = velocity[j] > 1e-9 ? 1 : velocity[j] < -1e-9 ? -1 : 0;
      if (direction != 0) {
        if (direction_[j] != 0 && direction != direction_[j]) ++summary_.reversals[j];
        direction_[j] = direction;
      }
      if (count_ > 1) {
        const double accel = std::abs(velocity[j] - previous_velocity_[j]) / h;
        last_accel_[j] = accel;
        if (accel > summary_.max_accel[j]) summary_.max_accel[j] = accel;
        if (accel > summary_.max_actuator_accel)
          summary_.max_actuator_accel = accel, summary_.max_accel_line = tick.line;
      }
    }
    previous_velocity_ = velocity;
    add_feed_ratio(tick);
    const double path_accel = (tick.path_speed - previous_path_speed_) / h;
    summary_.max_path_accel = std::max(summary_.max_path_accel, std::abs(path_accel));
    if (count_ > 1)
      summary_.max_path_jerk =
          std::max(summary_.max_path_jerk, std::abs(path_accel - previous_path_accel_) / h);
    previous_path_accel_ = path_accel;
    previous_path_speed_ = tick.path_speed;

    if (evaluate_error_) add_path_error(tick);
  }
  previous_.actuators = tick.actuators;
  previous_.position_mm = tick.pose.position_mm;
  previous_.s = tick.s;
  previous_.segment = tick.segment;
  previous_.feed_cap = last_feed_cap_;
  ++count_;
  summary_.ticks = count_;
  summary_.duration_s = tick.time_s;
  summary_.end_pose = tick.pose;
}

// Path speed against the feed of the segment the tick is on (and the one it came from).
void RunMonitor::add_feed_ratio(const ServoTick& tick) {
  const double h = plan_.period_s;
  summary_.max_path_speed = std::max(summary_.max_path_speed, tick.path_speed);
  double cap = last_feed_cap_;
  if (previous_.segment != tick.segment) cap = std::max(cap, previous_.feed_cap);
  if (cap > 0.0) {
    const double ratio = tick.path_speed / cap;
    // The speed is a difference of two arc lengths from the jerk filter's running sum of n samples, whose
    // rounding grows with the distance travelled: up to about n·ε·s in each, re-summed every n ticks. On a
    // long program (tens of metres, s ≈ 1e4–1e5 mm) that exceeds kFeedRatioRounding of a slow feed.
    const double window = std::max(1, plan_.filter_ticks);
    const double position_rounding =
        2.0 * (window + 2.0) * std::numeric_limits<double>::epsilon() * std::abs(tick.s);
    const double allowance = kFeedRatioRounding + position_rounding / (h * cap);
    last_feed_ratio_ = ratio > 1.0 && ratio <= 1.0 + allowance ? 1.0 : ratio;
    summary_.max_feed_ratio = std::max(summary_.max_feed_ratio, last_feed_ratio_);
  }
}

// The path error at the mid-period before `tick`: FK of the mean of the two ticks' actuators against the
// path.
void RunMonitor::add_path_error(const ServoTick& tick) {
  // The drives move linearly between setpoints: the largest deviation is near mid-period.
  const ActuatorVector middle = 0.5 * (tick.actuators + previous_.actuators);
  ErrorCode failure = ErrorCode::not_converged;
  if (machine_.mechanism->forward_warm_quiet(middle, fk_guess_, FkOptions{}, *fk_workspace_, fk_solution_,
                                             failure)) {
    const FkSolution* fk = &fk_solution_;
    fk_guess_ = fk->pose;
    // The stream's point where it gave one (it may run on another thread than this monitor).
    int hint = previous_.segment;
    const path::PathPoint on_path =
        tick.has_mid_point ? tick.mid_point : plan_.path.evaluate(0.5 * (tick.s + previous_.s), hint);
    Eigen::Vector3d error = fk->pose.position_mm - on_path.position_mm;
    // Reduced-DOF mechanisms: the coordinates they do not control follow, and are no error.
    const AxisMask axes = machine_.mechanism->controlled_axes();
    for (int c = 0; c < 3; ++c) {
      if (!axes.controlled[c]) error[c] = 0.0;
    }
    const Eigen::Vector3d chord = tick.pose.position_mm - previous_.position_mm;
    if (chord.norm() > 1e-12) {  // perpendicular part: lag along the path is not a contour error
      const Eigen::Vector3d t = chord.normalized();
      error -= error.dot(t) * t;
    }
    last_path_error_mm_ = error.norm();
    if (error.norm() > summary_.max_path_error_mm) {
      summary_.max_path_error_mm = error.norm();
      summary_.max_path_error_line = tick.line;
    }
    if (axes.controlled[5] && axes.controlled[3] == axes.controlled[4])  // all angles, or planar φ
      add_orientation_error(fk->pose.rotation, on_path.rotation.toRotationMatrix());
  } else {
    last_fk_failed_ = true;
    ++summary_.fk_failures;
  }
}

void RunMonitor::add_orientation_error(const Eigen::Matrix3d& actual, const Eigen::Matrix3d& on_path) {
  last_orientation_ = rotation_angle_between(actual, on_path);
  if (last_orientation_.exceeds(max_orientation_)) {
    max_orientation_ = last_orientation_;
    summary_.max_orientation_error_deg = max_orientation_.degrees();
  }
}

double RunMonitor::last_orientation_error_deg() const {
  return last_orientation_.degrees();  // NaN where not evaluated
}

}  // namespace pkm::planning
