#pragma once
// The analyses that listen to a planned run's servo ticks (planning/tick_observer.hpp): the drive forces,
// power and energy (dynamics/run_dynamics.hpp), the elastic machine's response (dynamics/run_elastic.hpp) and
// the tool's deflection under the process load (stiffness/run_deflection.hpp). The motion core streams the
// ticks and knows none of them; the caller chooses which listen (PlanAnalysisOptions) and where their ticks
// go (PlanAnalysisSinks).
#include <functional>
#include <optional>
#include <span>

#include "dynamics/run_dynamics.hpp"
#include "dynamics/run_elastic.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/plan_stream.hpp"
#include "statics/load_model.hpp"
#include "stiffness/run_deflection.hpp"

namespace pkm::analyses {

struct PlanAnalysisOptions {
  /// The rigid-body drive forces, power and energy at every tick (the machine file's `dynamics:`).
  bool dynamics = false;
  /// With `dynamics`: the elastic machine's response to the planned actuator motion (the struts' stiffness).
  bool elastic = false;
  /// The tool's deflection under `load`, the struts as springs.
  bool stiffness = false;
  /// The process load on the tool (nullptr: gravity only, and no deflection); must outlive the run.
  const statics::LoadModel* load = nullptr;
};

/// Where each analysis hands its evaluated ticks, in order; an empty member is not called.
struct PlanAnalysisSinks {
  std::function<Status(const dynamics::TickDynamics&)> dynamics;
  std::function<Status(const dynamics::ElasticTick&)> elastic;
  std::function<Status(const stiffness::DeflectionTick&)> deflection;
};

/// What a planned run measured: the motion (the run monitor's) and each analysis that listened.
struct PlanRun {
  planning::RunSummary motion;
  std::optional<dynamics::RunDynamicsSummary> dynamics;
  std::optional<dynamics::ElasticRunSummary> elastic;
  std::optional<stiffness::DeflectionSummary> deflection;
};

/// Streams `plan` (planning::stream_plan) with the analyses `options` names listening first and `observers`
/// after them. Refuses an analysis the machine file lacks the data for (naming its section and key); an
/// analysis' error at a tick names the program file and line.
Result<PlanRun> stream_plan_with_analyses(const planning::MotionPlan& plan, const Machine& machine,
                                          const planning::StreamOptions& stream,
                                          const PlanAnalysisOptions& options, const PlanAnalysisSinks& sinks,
                                          std::span<planning::TickObserver* const> observers = {});

}  // namespace pkm::analyses
