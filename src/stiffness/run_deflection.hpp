#pragma once
// The tool's deflection under the process load along a planned run (how far this program's
// surface will be off): at every servo tick the compliance of the commanded pose (compliance_model.hpp, the
// machine file's stiffness model) times the cutting load there (statics/load_model.hpp, its direction of
// travel from the ticks' central differences, as the dynamics take it) gives the tool point's displacement
// and the platform's turn. The surface error is the displacement along the surface normal, taken as the tool
// axis (Rusanov's setting: a ball-end mill with its axis on the surface normal). One tick behind the stream:
// tick k is evaluated when tick k + 1 arrives. Quasi-static: no inertia, the drives hold their positions, the
// frame's nodes and the struts' ends moving with it statically.
#include <array>
#include <functional>

#include "core/tick_window.hpp"
#include "machine/machine.hpp"
#include "statics/load_model.hpp"
#include "stiffness/compliance_model.hpp"
#include "stiffness/tool_deflection.hpp"

namespace pkm::stiffness {

struct DeflectionTick {
  double time_s = 0.0;
  int line = 0;
  Eigen::Vector3d deflection_mm = Eigen::Vector3d::Zero();  ///< of the tool point, base frame
  double normal_mm = 0.0;     ///< along the tool axis (away from the work when positive)
  double rotation_rad = 0.0;  ///< the platform's turn
  statics::Wrench load;       ///< the load that caused it
};

/// The statistics over the ticks (points = ticks), the time of the largest normal error and the model.
struct DeflectionSummary : DeflectionStatistics {
  double max_normal_time_s = 0.0;
  StiffnessModel model = StiffnessModel::struts;
};

class RunDeflection {
 public:
  /// Fails as strut_stiffness_of does (no stiffness for the struts: the machine file and key). `load` must
  /// outlive the run.
  static Result<RunDeflection> make(const Machine& machine, const statics::LoadModel& load,
                                    std::function<Status(const DeflectionTick&)> on_tick);
  /// The next commanded pose (`cutting`: false on rapids). Fails where the compliance is unbounded (a
  /// singular pose), naming the program line in the error's location.
  Status add(double time_s, int line, const Pose& pose, bool cutting = true);
  /// Evaluates the last tick (at rest); call once after the last add().
  Status finish();
  const DeflectionSummary& summary() const { return summary_; }

 private:
  RunDeflection(const Machine& machine, const statics::LoadModel& load, ComplianceModel model,
                std::function<Status(const DeflectionTick&)> on_tick);
  Status evaluate(int index_in_window, bool at_rest);

  const statics::LoadModel* load_;
  ComplianceModel model_;
  std::function<Status(const DeflectionTick&)> on_tick_;
  Eigen::Vector3d tool_axis_platform_;
  using Sample = CommandedTick;
  TickWindow<Sample> window_;
  DeflectionSummary summary_;
};

}  // namespace pkm::stiffness
