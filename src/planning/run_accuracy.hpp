#pragma once
// What a plan claims at every servo tick, and the refusal when a tick breaks it. The actuators' set points
// are what the machine will do; the forward kinematics of the drives' motion (at mid-period, where the
// straight-line motion between set points deviates most) must stay on the planned path within the blend
// tolerance, and keep the planned orientation where the mechanism controls it. A plan that does not, because
// its path crosses a singularity into another assembly mode, or the mechanism cannot follow it, is refused at
// the program line of the first tick that breaks it: it never leaves pkm as a plan.
#include "core/result.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/run_monitor.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::planning {

/// The path-error bound when the blend tolerance is 0 (exact stops): the planner keeps the chord error
/// between set points within a tenth of the tolerance, at least 0.1 µm; a micrometre leaves room for the
/// forward kinematics' convergence and the blend's rounding.
inline constexpr double kMinPathErrorBoundMm = 1e-3;
/// The orientation error a plan may have at mid-period where the mechanism sets the orientation: about a
/// micrometre of tool-point motion 10 mm from the platform.
inline constexpr double kOrientationErrorBoundDeg = 0.01;

/// Relative excess over an actuator speed or acceleration limit that is the rounding of finite differences
/// at the servo rate, not a broken limit.
inline constexpr double kLimitRounding = 1e-9;

/// The path error every tick of `plan` must hold: its blend tolerance, at least kMinPathErrorBoundMm.
double path_error_bound_mm(const MotionPlan& plan);

/// Ok while the tick the monitor measured last holds every limit (actuator range, speed and acceleration, the
/// programmed feed: ErrorCode::limit_exceeded) and, with `path_error_evaluated`, the path and orientation
/// bounds (its errors NaN: not evaluated, or the first tick; ErrorCode::unreachable). Errors are at the
/// tick's program line, with the value, the bound and where.
Status check_tick(const MotionPlan& plan, const Machine& machine, const ServoTick& tick,
                  const RunMonitor& monitor, bool path_error_evaluated);

}  // namespace pkm::planning
