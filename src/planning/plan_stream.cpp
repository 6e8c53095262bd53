#include "planning/plan_stream.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "planning/run_accuracy.hpp"

namespace pkm::planning {

namespace {

/// The program file and line of an error at a program line, for messages ("FILE:LINE: …").
Error at_program_line(const MotionPlan& plan, const Error& error) {
  Error located = error;
  located.message = fmt::format("{}:{}: {}", plan.program_source, error.location.line, error.message);
  located.location.file = plan.program_source;
  return located;
}

}  // namespace

Result<RunSummary> stream_plan(const MotionPlan& plan, const Machine& machine, const OutputOptions& options,
                               const PlanTickObservers& observers) {
  const auto forward = [](const auto& observer) {
    return [&observer](const auto& tick) -> Status { return observer ? observer(tick) : ok_status(); };
  };
  std::optional<dynamics::RunDynamics> drive_dynamics;
  if (options.dynamics) {
    if (Status given = dynamics::require_dynamics_section(machine); !given) return given.error();
    drive_dynamics.emplace(machine, plan.period_s, forward(observers.dynamics), options.dynamics_load);
  }
  std::optional<dynamics::RunElastic> elastic;
  if (options.dynamics && options.elastic) {
    auto made = dynamics::RunElastic::make(machine, plan.period_s, forward(observers.elastic), {},
                                           options.dynamics_load);
    if (!made) return made.error();
    elastic.emplace(std::move(*made));
  }
  std::optional<stiffness::RunDeflection> deflection;
  if (options.stiffness) {
    static const statics::LoadModel kNoLoad;
    auto made = stiffness::RunDeflection::make(
        machine, options.dynamics_load != nullptr ? *options.dynamics_load : kNoLoad,
        forward(observers.deflection));
    if (!made) return made.error();
    deflection.emplace(std::move(*made));
  }

  ServoStream stream(plan, machine);
  RunMonitor monitor(plan, machine, options.override_pct, options.evaluate_path_error);
  const long total = stream.tick_count();
  const long report_every = std::clamp(total / 1000, 1L, 4096L);
  ServoTick tick;
  while (stream.next(tick)) {
    monitor.add(tick);
    if (Status held = check_tick(plan, machine, tick, monitor, options.evaluate_path_error); !held)
      return held.error();
    const bool cutting = !plan.path.segments[tick.segment].rapid;
    if (drive_dynamics) {
      if (Status added = drive_dynamics->add(tick.time_s, tick.line, tick.pose, cutting); !added) {
        return at_program_line(plan, added.error());
      }
    }
    if (elastic) {
      if (Status added = elastic->add(tick.time_s, tick.line, tick.pose, tick.actuators, cutting); !added) {
        return at_program_line(plan, added.error());
      }
    }
    if (deflection) {
      if (Status added = deflection->add(tick.time_s, tick.line, tick.pose, cutting); !added) {
        return at_program_line(plan, added.error());
      }
    }
    if (observers.tick) {
      if (Status kept = observers.tick(tick, monitor); !kept) return kept.error();
    }
    if (options.progress && tick.index % report_every == 0)
      report_progress(options.progress, "writing the outputs", static_cast<double>(tick.index) / total,
                      tick.line);
  }
  if (stream.error()) return *stream.error();
  report_progress(options.progress, "writing the outputs", 1.0);
  RunSummary run = monitor.summary();
  if (drive_dynamics) {
    if (Status finished = drive_dynamics->finish(); !finished) return at_program_line(plan, finished.error());
    run.dynamics = drive_dynamics->summary();
  }
  if (elastic) {
    if (Status finished = elastic->finish(); !finished) return at_program_line(plan, finished.error());
    run.elastic = elastic->summary();
  }
  if (deflection) {
    if (Status finished = deflection->finish(); !finished) return at_program_line(plan, finished.error());
    run.deflection = deflection->summary();
  }
  return run;
}

}  // namespace pkm::planning
