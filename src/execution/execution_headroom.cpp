#include "execution/execution_headroom.hpp"

#include <fmt/format.h>

#include <cmath>

#include "execution/step_executor.hpp"

namespace pkm::execution {

Result<ExecutionHeadroom> execution_headroom(const DriveLimits& limits, double max_override,
                                             double motion_share, double period_s) {
  if (!(limits.speed > 0.0) || !(limits.accel > 0.0) || (limits.jerk && !(*limits.jerk > 0.0)))
    return make_error(ErrorCode::bad_input,
                      "executing a program needs the drives' speed and acceleration limits");
  if (!(max_override >= 1.0) || !(motion_share > 0.0 && motion_share < 1.0) || !(period_s > 0.0))
    return make_error(ErrorCode::bad_input,
                      fmt::format("the largest override must be ≥ 100 % and the motion's share of the "
                                  "acceleration between 0 and 1 (got {} %, {})",
                                  100.0 * max_override, motion_share));
  ExecutionHeadroom h;
  h.max_override = max_override;
  h.motion_share = motion_share;
  const double k = max_override, eta = motion_share;
  h.nominal.speed = limits.speed / k;
  h.nominal.accel = eta * limits.accel / (k * k);
  h.rates.max_rate_per_s = (1.0 - eta) * limits.accel / h.nominal.speed;
  if (limits.jerk) {
    h.nominal.jerk = eta * *limits.jerk / (k * k * k);
    const double left = (1.0 - eta) * *limits.jerk - 3.0 * h.nominal.accel * k * h.rates.max_rate_per_s;
    if (!(left > 0.0)) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("the jerk limit {:.6g}/s³ leaves no room to change the feed override with "
                      "the acceleration {:.6g}/s² and speed {:.6g}/s: raise it above {:.6g}/s³",
                      *limits.jerk, limits.accel, limits.speed, *limits.jerk - left / (1.0 - eta)));
    }
    h.rates.max_accel_per_s2 = left / h.nominal.speed;
  } else {
    h.rates.max_accel_per_s2 = h.rates.max_rate_per_s / kRateRiseS;
  }
  // The window must hold the motion K needs to stop from K_max (StepExecutor::stopping_distance_periods).
  const double stop_s = k / h.rates.max_rate_per_s + h.rates.max_rate_per_s / h.rates.max_accel_per_s2;
  const double stop_periods = k * stop_s / period_s + 2.0;
  if (stop_periods >= StepExecutor::kWindow) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("a feed hold from {} % takes {:.0f} servo periods, more than the executor "
                                  "holds ({}): the acceleration limit is too low for this servo period",
                                  100.0 * k, stop_periods, StepExecutor::kWindow));
  }
  return h;
}

}  // namespace pkm::execution
