#include "planning/run_accuracy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/units.hpp"
#include "planning/path_sampling.hpp"

namespace pkm::planning {

namespace {

Error tick_error(ErrorCode code, const MotionPlan& plan, const ServoTick& tick, const std::string& what) {
  return Error{code,
               fmt::format("{}:{}: at t = {:.3f} s {}", plan.program_source, tick.line, tick.time_s, what),
               ErrorLocation{plan.program_source, tick.line, 0, ""}};
}

/// The forward kinematics of the drives' motion against the planned path and orientation.
Status check_tick_path(const MotionPlan& plan, const Machine& machine, const ServoTick& tick,
                       const RunMonitor& monitor) {
  // The pose's text only when a check fails: formatting it (and its angles) at every tick cost more than
  // the tick's inverse kinematics.
  const auto near = [&] { return program_pose_text(machine, tick.pose); };
  if (monitor.last_fk_failed()) {
    return tick_error(ErrorCode::unreachable, plan, tick,
                      fmt::format("near {} the forward kinematics of the planned actuator motion did not "
                                  "converge: the plan cannot be verified there (a singular configuration)",
                                  near()));
  }
  const double bound_mm = path_error_bound_mm(plan);
  if (const double error_mm = monitor.last_path_error_mm(); error_mm > bound_mm) {
    return tick_error(
        ErrorCode::unreachable, plan, tick,
        fmt::format(
            "near {} the planned actuator motion puts the tool {:.4g} mm off the path (tolerance {:g} "
            "mm): the path crosses a singularity or another assembly mode of the mechanism; limits in "
            "the machine file keep plans out of such regions",
            near(), error_mm, bound_mm));
  }
  static const RotationAngle orientation_bound = RotationAngle::of_degrees(kOrientationErrorBoundDeg);
  if (monitor.last_orientation_error_exceeds(orientation_bound)) {
    const double error_deg = monitor.last_orientation_error_deg();
    return tick_error(
        ErrorCode::unreachable, plan, tick,
        fmt::format("near {} the planned actuator motion turns the tool {:.4g} deg away from the "
                    "programmed orientation (bound {:g} deg): the path crosses a singularity or "
                    "another assembly mode of the mechanism",
                    near(), error_deg, kOrientationErrorBoundDeg));
  }
  return ok_status();
}

/// The actuator range, speed and acceleration and the programmed feed at one tick.
Status check_tick_limits(const MotionPlan& plan, const Machine& machine, const ServoTick& tick,
                         const RunMonitor& monitor) {
  if (Status range = check_actuator_range(machine, tick.actuators); !range)
    return tick_error(ErrorCode::limit_exceeded, plan, tick, range.error().message);
  const bool angular = machine.mechanism->actuators_are_angles();
  const double scale = angular ? deg_from_rad(1.0) : 1.0;
  const char* unit = angular ? "deg" : "mm";
  const auto over = [](double value, const std::optional<double>& limit) {
    return limit && value > *limit * (1.0 + kLimitRounding);
  };
  const ActuatorLimits& limits = machine.limits;
  for (int j = 0; j < static_cast<int>(tick.actuators.size()); ++j) {
    const double speed = std::abs(monitor.last_velocity()[j]);
    if (over(speed, limits.speed)) {
      return tick_error(
          ErrorCode::limit_exceeded, plan, tick,
          fmt::format("actuator {} moves at {:.4f} {}/s, over actuator_speed {:g} {}/s ({}:{})", j + 1,
                      speed * scale, unit, *limits.speed * scale, unit, machine.source, limits.speed_line));
    }
    const double accel = monitor.last_accel()[j];
    if (over(accel, limits.accel)) {
      return tick_error(
          ErrorCode::limit_exceeded, plan, tick,
          fmt::format("actuator {} accelerates at {:.4f} {}/s², over actuator_accel {:g} {}/s² ({}:{})",
                      j + 1, accel * scale, unit, *limits.accel * scale, unit, machine.source,
                      limits.accel_line));
    }
  }
  if (monitor.last_feed_ratio() > 1.0 + kFeedRatioRounding) {
    return tick_error(
        ErrorCode::limit_exceeded, plan, tick,
        fmt::format("the tool moves at {:.6f} % of the programmed feed", 100.0 * monitor.last_feed_ratio()));
  }
  return ok_status();
}

}  // namespace

double path_error_bound_mm(const MotionPlan& plan) {
  return std::max(plan.path_tolerance_mm, kMinPathErrorBoundMm);
}

Status check_tick(const MotionPlan& plan, const Machine& machine, const ServoTick& tick,
                  const RunMonitor& monitor, bool path_error_evaluated) {
  if (path_error_evaluated) {
    if (Status path = check_tick_path(plan, machine, tick, monitor); !path) return path;
  }
  return check_tick_limits(plan, machine, tick, monitor);
}

}  // namespace pkm::planning
