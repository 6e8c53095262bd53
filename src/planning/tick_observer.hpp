#pragma once
// The one way out of a streamed run: whatever wants the servo ticks (an analysis, a file, an array in Python)
// listens as a TickObserver. The motion core streams and measures the ticks (plan_stream.hpp) and knows none
// of its listeners; the caller decides which listen.
#include <functional>
#include <utility>

#include "core/result.hpp"
#include "planning/run_monitor.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::planning {

class TickObserver {
 public:
  virtual ~TickObserver() = default;
  /// Once, before the first tick, with the number of ticks the run will stream (for listeners that keep
  /// every tick: one allocation up front instead of growing as they come), or 0 when the plan is still being
  /// made as the ticks stream and their number is not known yet. An error stops the run.
  virtual Status on_start(long /*tick_count*/) { return ok_status(); }
  /// Every tick in order, after the run monitor measured it (its last_…() values are the tick's). An error
  /// stops the run.
  virtual Status on_tick(const ServoTick& tick, const RunMonitor& monitor) = 0;
  /// Once, after the last tick, when the whole run streamed.
  virtual Status on_finish() { return ok_status(); }
};

/// A function as a tick observer.
class TickFunction final : public TickObserver {
 public:
  using Function = std::function<Status(const ServoTick&, const RunMonitor&)>;
  explicit TickFunction(Function function) : function_(std::move(function)) {}
  Status on_tick(const ServoTick& tick, const RunMonitor& monitor) override {
    return function_(tick, monitor);
  }

 private:
  Function function_;
};

}  // namespace pkm::planning
