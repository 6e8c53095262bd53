#pragma once
// The tool's deflection under the process load along a planned run (issue 15: "how far will this program's
// surface be off"): at every servo tick the strut-only compliance of the commanded pose
// (strut_compliance.hpp) times the cutting load there (statics/load_model.hpp, its direction of travel from
// the ticks' central differences, as the dynamics take it) gives the tool point's displacement and the
// platform's turn. The surface error is the displacement along the surface normal, taken as the tool axis
// (the seed's setting: a ball-end mill with its axis on the surface normal). One tick behind the stream: tick
// k is evaluated when tick k + 1 arrives. Quasi-static: no inertia, the drives hold their positions, the
// joints and frame rigid.
#include <array>
#include <functional>

#include "core/tick_window.hpp"
#include "machine/machine.hpp"
#include "statics/load_model.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

struct DeflectionTick {
  double time_s = 0.0;
  int line = 0;
  Eigen::Vector3d deflection_mm = Eigen::Vector3d::Zero();  ///< of the tool point, base frame
  double normal_mm = 0.0;     ///< along the tool axis (away from the work when positive)
  double rotation_rad = 0.0;  ///< the platform's turn
  statics::Wrench load;       ///< the load that caused it
};

struct DeflectionSummary {
  double max_normal_mm = 0.0;  ///< largest |normal deflection|
  int max_normal_line = 0;
  double max_normal_time_s = 0.0;
  double rms_normal_mm = 0.0;      ///< over the cutting ticks
  double max_deflection_mm = 0.0;  ///< largest |deflection|
  int max_deflection_line = 0;
  long ticks = 0;
  long cutting_ticks = 0;
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
  RunDeflection(const Machine& machine, const statics::LoadModel& load, StiffnessParameters stiffness,
                std::function<Status(const DeflectionTick&)> on_tick);
  Status evaluate(int index_in_window, bool at_rest);

  const Machine* machine_;
  const statics::LoadModel* load_;
  StiffnessParameters stiffness_;
  std::function<Status(const DeflectionTick&)> on_tick_;
  Eigen::Vector3d tool_axis_platform_;
  using Sample = CommandedTick;
  TickWindow<Sample> window_;
  double normal_square_sum_ = 0.0;
  DeflectionSummary summary_;
};

}  // namespace pkm::stiffness
