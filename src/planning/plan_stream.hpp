#pragma once
// A planned run at the servo rate, tick by tick, with what the options ask to evaluate along it (the run
// monitor's limits and path error, the drive forces, the elastic response, the tool's deflection), handed to
// observers: the output files (plan_output.hpp) and callers that keep the ticks in memory (the Python module)
// run the same loop.
#include <functional>

#include "dynamics/run_dynamics.hpp"
#include "dynamics/run_elastic.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/plan_output.hpp"
#include "planning/run_monitor.hpp"
#include "planning/servo_stream.hpp"
#include "stiffness/run_deflection.hpp"

namespace pkm::planning {

/// Where each tick's results go; an empty member is not called. A failing observer stops the run.
struct PlanTickObservers {
  /// Every tick, after the monitor measured it (its last_feed_cap() and last_path_error_mm() are the tick's).
  std::function<Status(const ServoTick&, const RunMonitor&)> tick;
  std::function<Status(const dynamics::TickDynamics&)> dynamics;       ///< with OutputOptions::dynamics
  std::function<Status(const dynamics::ElasticTick&)> elastic;         ///< with OutputOptions::elastic
  std::function<Status(const stiffness::DeflectionTick&)> deflection;  ///< with OutputOptions::stiffness
};

/// Streams `plan` and returns the run's summary; errors at a program line name the program file.
Result<RunSummary> stream_plan(const MotionPlan& plan, const Machine& machine, const OutputOptions& options,
                               const PlanTickObservers& observers);

}  // namespace pkm::planning
