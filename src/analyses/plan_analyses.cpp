#include "analyses/plan_analyses.hpp"

#include <vector>

namespace pkm::analyses {

namespace {

/// A sink that may be empty, as the analyses take it.
template <class Tick>
std::function<Status(const Tick&)> forward_to(const std::function<Status(const Tick&)>& sink) {
  return [&sink](const Tick& tick) -> Status { return sink ? sink(tick) : ok_status(); };
}

/// One analysis listening to the ticks: `feed` hands it a tick; its errors are located at the program line.
template <class Run>
class AnalysisObserver final : public planning::TickObserver {
 public:
  using Feed = Status (*)(Run&, const planning::ServoTick&, bool cutting);
  AnalysisObserver(const planning::MotionPlan& plan, Run& run, Feed feed)
      : plan_(plan), run_(run), feed_(feed) {}

  Status on_tick(const planning::ServoTick& tick, const planning::RunMonitor&) override {
    const bool cutting = !tick.on_segment.rapid;
    if (Status added = feed_(run_, tick, cutting); !added)
      return planning::at_program_line(plan_, added.error());
    return ok_status();
  }
  Status on_finish() override {
    if (Status finished = run_.finish(); !finished) return planning::at_program_line(plan_, finished.error());
    return ok_status();
  }

 private:
  const planning::MotionPlan& plan_;
  Run& run_;
  Feed feed_;
};

Status feed_dynamics(dynamics::RunDynamics& run, const planning::ServoTick& tick, bool cutting) {
  return run.add(tick.time_s, tick.line, tick.pose, cutting);
}
Status feed_elastic(dynamics::RunElastic& run, const planning::ServoTick& tick, bool cutting) {
  return run.add(tick.time_s, tick.line, tick.pose, tick.actuators, cutting);
}
Status feed_deflection(stiffness::RunDeflection& run, const planning::ServoTick& tick, bool cutting) {
  return run.add(tick.time_s, tick.line, tick.pose, cutting);
}

}  // namespace

Result<PlanRun> stream_plan_with_analyses(const planning::MotionPlan& plan, const Machine& machine,
                                          const planning::StreamOptions& stream,
                                          const PlanAnalysisOptions& options, const PlanAnalysisSinks& sinks,
                                          std::span<planning::TickObserver* const> observers) {
  std::optional<dynamics::RunDynamics> drive_dynamics;
  if (options.dynamics) {
    if (Status given = dynamics::require_dynamics_section(machine); !given) return given.error();
    drive_dynamics.emplace(machine, plan.period_s, forward_to(sinks.dynamics), options.load);
  }
  std::optional<dynamics::RunElastic> elastic;
  if (options.dynamics && options.elastic) {
    auto made =
        dynamics::RunElastic::make(machine, plan.period_s, forward_to(sinks.elastic), {}, options.load);
    if (!made) return made.error();
    elastic.emplace(std::move(*made));
  }
  std::optional<stiffness::RunDeflection> deflection;
  if (options.stiffness) {
    static const statics::LoadModel kNoLoad;
    auto made = stiffness::RunDeflection::make(machine, options.load != nullptr ? *options.load : kNoLoad,
                                               forward_to(sinks.deflection));
    if (!made) return made.error();
    deflection.emplace(std::move(*made));
  }

  std::optional<AnalysisObserver<dynamics::RunDynamics>> dynamics_observer;
  std::optional<AnalysisObserver<dynamics::RunElastic>> elastic_observer;
  std::optional<AnalysisObserver<stiffness::RunDeflection>> deflection_observer;
  std::vector<planning::TickObserver*> listening;
  if (drive_dynamics) listening.push_back(&dynamics_observer.emplace(plan, *drive_dynamics, feed_dynamics));
  if (elastic) listening.push_back(&elastic_observer.emplace(plan, *elastic, feed_elastic));
  if (deflection) listening.push_back(&deflection_observer.emplace(plan, *deflection, feed_deflection));
  listening.insert(listening.end(), observers.begin(), observers.end());

  auto motion = planning::stream_plan(plan, machine, stream, listening);
  if (!motion) return motion.error();
  PlanRun run;
  run.motion = std::move(*motion);
  if (drive_dynamics) run.dynamics = drive_dynamics->summary();
  if (elastic) run.elastic = elastic->summary();
  if (deflection) run.deflection = deflection->summary();
  return run;
}

}  // namespace pkm::analyses
