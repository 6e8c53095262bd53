#pragma once
// A planned run at the servo rate, tick by tick: each tick measured by the run monitor (limits, path error)
// and checked against what the plan claims (run_accuracy.hpp), then handed to the observers in order. The
// output files, the analyses (drive forces, elastic response, deflection) and in-memory arrays listen through
// the same interface (tick_observer.hpp).
#include <span>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/run_monitor.hpp"
#include "planning/tick_observer.hpp"

namespace pkm::planning {

class PlanProducer;

struct StreamOptions {
  double override_pct = 100.0;
  /// FK of the actuators at every mid-period: the path and orientation errors (run_monitor.hpp).
  bool evaluate_path_error = true;
  /// Told now and then how far the stream is and at which program line (core/progress.hpp).
  ProgressSink progress;
  /// Where the plan is a window planned as it streams, its planner (plan_producer.hpp); null: a whole plan.
  PlanProducer* source = nullptr;
};

/// Streams `plan` to `observers` and returns what the monitor measured. A tick that breaks a limit or the
/// path bound, a failing inverse kinematics or a failing observer stops the run with its error.
Result<RunSummary> stream_plan(const MotionPlan& plan, const Machine& machine, const StreamOptions& options,
                               std::span<TickObserver* const> observers = {});

/// `error` at a program line, as "FILE:LINE: message" with the plan's program file.
Error at_program_line(const MotionPlan& plan, const Error& error);

}  // namespace pkm::planning
