#include "planning/plan_stream.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <optional>
#include <thread>

#include "core/thread_priority.hpp"
#include "planning/plan_producer.hpp"
#include "planning/run_accuracy.hpp"
#include "planning/tick_queue.hpp"

namespace pkm::planning {

Error at_program_line(const MotionPlan& plan, const Error& error) {
  Error located = error;
  located.message = fmt::format("{}:{}: {}", plan.program_source, error.location.line, error.message);
  located.location.file = plan.program_source;
  return located;
}

namespace {

/// The ticks from `next` (a tick, valid until the next call, or null after the last) measured, checked and
/// handed to the observers: the run's loop, whichever thread makes the ticks.
template <class NextTick>
Status measure_and_hand_on(const MotionPlan& plan, const Machine& machine, const StreamOptions& options,
                           std::span<TickObserver* const> observers, long total, RunMonitor& monitor,
                           NextTick&& next) {
  // Streamed from a source still planning, the ticks are not counted until the plan ends: the progress is
  // then the share of the program's lines the ticks have passed.
  const long report_every = total > 0 ? std::clamp(total / 1000, 1L, 4096L) : 4096L;
  const int lines = options.source != nullptr ? std::max(1, options.source->line_count()) : 1;
  auto fraction_done = [&](const ServoTick& tick) {
    return total > 0 ? static_cast<double>(tick.index) / total : std::min(1.0, double(tick.line) / lines);
  };
  for (TickObserver* observer : observers) {
    if (Status started = observer->on_start(total); !started) return started;
  }
  while (const ServoTick* next_tick = next()) {
    const ServoTick& tick = *next_tick;
    monitor.add(tick);
    if (Status held = check_tick(plan, machine, tick, monitor, options.evaluate_path_error); !held)
      return held;
    for (TickObserver* observer : observers) {
      if (Status kept = observer->on_tick(tick, monitor); !kept) return kept;
    }
    if (options.progress && tick.index % report_every == 0)
      report_progress(options.progress, "writing the outputs", fraction_done(tick), tick.line,
                      tick.index + 1);
  }
  return ok_status();
}

/// The planner and the stream on a thread of their own, the monitor and the observers on this one: the
/// consumer reads only the ticks (ServoTick::on_segment, mid_point), never the plan's window.
Status stream_on_two_threads(const MotionPlan& plan, const Machine& machine, const StreamOptions& options,
                             std::span<TickObserver* const> observers, ServoStream& stream,
                             RunMonitor& monitor) {
  TickQueue queue(256, 32);
  std::thread producer([&] {
    // The consumer (forward kinematics, checks, rows) is the run's longest thread; ticks made ahead can wait.
    constexpr int kProducerNiceSteps = 5;
    lower_this_thread_priority(kProducerNiceSteps);
    std::optional<Error> failed;
    try {
      // Each tick is made where the consumer will read it.
      while (stream.next(queue.slot()))
        if (!queue.commit()) break;
      failed = stream.error();
    } catch (const std::exception& e) {
      failed = Error{ErrorCode::io, fmt::format("the servo stream stopped: {}", e.what())};
    }
    queue.close(std::move(failed));
  });
  // Stops and joins the producer however this thread leaves (an observer may throw).
  struct Joined {
    TickQueue& queue;
    std::thread& thread;
    ~Joined() {
      queue.cancel();
      thread.join();
    }
  };
  {
    const Joined joined{queue, producer};
    const Status consumed =
        measure_and_hand_on(plan, machine, options, observers, 0, monitor, [&queue] { return queue.next(); });
    if (!consumed) return consumed;
  }
  if (queue.error()) return *queue.error();
  return ok_status();
}

}  // namespace

Result<RunSummary> stream_plan(const MotionPlan& plan, const Machine& machine, const StreamOptions& options,
                               std::span<TickObserver* const> observers) {
  ServoStream stream(plan, machine, options.source);
  stream.with_mid_points(options.evaluate_path_error);
  RunMonitor monitor(plan, machine, options.override_pct, options.evaluate_path_error);
  if (options.source != nullptr) {
    if (Status streamed = stream_on_two_threads(plan, machine, options, observers, stream, monitor);
        !streamed)
      return streamed.error();
  } else {
    ServoTick tick;
    const Status streamed = measure_and_hand_on(
        plan, machine, options, observers, stream.tick_count(), monitor,
        [&stream, &tick]() -> const ServoTick* { return stream.next(tick) ? &tick : nullptr; });
    if (!streamed) return streamed.error();
    if (stream.error()) return *stream.error();
  }
  report_progress(options.progress, "writing the outputs", 1.0, 0, stream.tick_count());
  for (TickObserver* observer : observers) {
    if (Status finished = observer->on_finish(); !finished) return finished.error();
  }
  return monitor.summary();
}

}  // namespace pkm::planning
