#include "planning/plan_stream.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "planning/plan_producer.hpp"
#include "planning/run_accuracy.hpp"

namespace pkm::planning {

Error at_program_line(const MotionPlan& plan, const Error& error) {
  Error located = error;
  located.message = fmt::format("{}:{}: {}", plan.program_source, error.location.line, error.message);
  located.location.file = plan.program_source;
  return located;
}

Result<RunSummary> stream_plan(const MotionPlan& plan, const Machine& machine, const StreamOptions& options,
                               std::span<TickObserver* const> observers) {
  ServoStream stream(plan, machine, options.source);
  RunMonitor monitor(plan, machine, options.override_pct, options.evaluate_path_error);
  // Streamed from a source still planning, the ticks are not counted until the plan ends: the progress is
  // then the share of the program's lines the ticks have passed.
  const long total = stream.tick_count();
  const long report_every = total > 0 ? std::clamp(total / 1000, 1L, 4096L) : 4096L;
  const int lines = options.source != nullptr ? std::max(1, options.source->line_count()) : 1;
  auto fraction_done = [&](const ServoTick& tick) {
    return total > 0 ? static_cast<double>(tick.index) / total : std::min(1.0, double(tick.line) / lines);
  };
  for (TickObserver* observer : observers) {
    if (Status started = observer->on_start(total); !started) return started.error();
  }
  ServoTick tick;
  while (stream.next(tick)) {
    monitor.add(tick);
    if (Status held = check_tick(plan, machine, tick, monitor, options.evaluate_path_error); !held)
      return held.error();
    for (TickObserver* observer : observers) {
      if (Status kept = observer->on_tick(tick, monitor); !kept) return kept.error();
    }
    if (options.progress && tick.index % report_every == 0)
      report_progress(options.progress, "writing the outputs", fraction_done(tick), tick.line,
                      tick.index + 1);
  }
  if (stream.error()) return *stream.error();
  report_progress(options.progress, "writing the outputs", 1.0, 0, stream.tick_count());
  for (TickObserver* observer : observers) {
    if (Status finished = observer->on_finish(); !finished) return finished.error();
  }
  return monitor.summary();
}

}  // namespace pkm::planning
