#pragma once
// The elastic machine along a planned run (Smirnov 2019, §4.5: trajectory modelling, the dynamic error of
// the tool Δr_P = r_P^elastic(t) − r_P^FK(q(t))): the servo ticks' actuator positions are the drives'
// excitation q(t), the platform's response is integrated (elastic_simulation.hpp) and compared at every tick
// with the commanded pose, which is FK(q) of that tick. Between ticks q(t) is the cubic Hermite curve through
// the ticks' positions with central-difference slopes (Catmull–Rom, zero at the first and the last tick:
// every run starts and ends at rest, and the drives hold after the end), so q and q̇ are continuous and the
// integrator sees a smooth excitation. The run starts at rest in the static equilibrium of the first tick's
// drive positions, so the error holds the static sag under gravity (a few µm on the shipped machines) plus
// the vibration the motion excites. Steps are at most one servo period long and may pass the tick reported
// (dense output), so the response of tick k is reported when tick k + 2 arrives, the last two at finish().
// With a process load (statics/load_model.hpp), the cut acts on the platform as in run_dynamics.hpp, its
// direction of travel from the same central differences, linear between ticks: the response then holds the
// deflection under the cut as well.
#include <array>
#include <functional>
#include <memory>

#include "dynamics/elastic_simulation.hpp"
#include "machine/machine.hpp"
#include "statics/load_model.hpp"

namespace pkm::dynamics {

/// The response at one tick: the platform's deviation from the commanded pose.
struct ElasticTick {
  double time_s = 0.0;
  int line = 0;
  Eigen::Vector3d deviation_mm = Eigen::Vector3d::Zero();  ///< tool point, base frame (actual − commanded)
  double rotation_deg = 0.0;                               ///< angle of R_actual · R_commandedᵀ
  double tool_error_mm = 0.0;                              ///< |deviation|
};

struct ElasticRunSummary {
  double lowest_frequency_Hz = 0.0;  ///< at the first tick's pose, about its static equilibrium
  double start_deflection_mm = 0.0;  ///< the tool point's static sag there
  double max_tool_error_mm = 0.0;
  double max_tool_error_time_s = 0.0;
  int max_tool_error_line = 0;
  double max_rotation_deg = 0.0;
  long ticks = 0;
  IntegrationCounters counters;
};

class RunElastic {
 public:
  /// `period_s`: the ticks' spacing, the longest integration step. `on_tick` receives every tick's response
  /// in order (e.g. to write response.csv); it may be empty. Fails as make_elastic_model does (no dynamics
  /// section, a strut without stiffness: the machine file's key).
  /// `load`, when given, must outlive the run.
  static Result<RunElastic> make(const Machine& machine, double period_s,
                                 std::function<Status(const ElasticTick&)> on_tick,
                                 ElasticIntegration integration = {},
                                 const statics::LoadModel* load = nullptr);
  /// The next tick: commanded pose and the drives' positions for it (IK of the pose); `cutting` false on
  /// rapids, where no cutting load acts.
  Status add(double time_s, int line, const Pose& commanded, const ActuatorVector& actuators,
             bool cutting = true);
  /// Reports the last ticks (the drives at rest from the last tick on); call once after the last add().
  Status finish();
  const ElasticRunSummary& summary() const { return summary_; }

 private:
  struct Tick {
    double time_s = 0.0;
    int line = 0;
    Pose pose;
    ActuatorVector actuators;
    ActuatorVector slope;  ///< q̇ at the tick (known once the next tick is)
    bool cutting = true;
    statics::Wrench load;  ///< the process load at the tick (known with the slope)
  };

  /// The last ticks, and the drives through them: cubic Hermite between ticks whose slopes are known, held
  /// before the first and after the last (at rest).
  class TickHistory final : public DriveMotion {
   public:
    static constexpr long kRing = 4;  ///< ticks k − 3 … k: the steps in progress need no older ones
    Tick& at(long index) { return ring_[index % kRing]; }
    const Tick& at(long index) const { return ring_[index % kRing]; }
    void setpoint(double time_s, DriveSetpoint& out) const override;

    long count = 0;       ///< ticks added
    long with_slope = 0;  ///< ticks whose slope is known: q(t) is known up to the last of them
    bool finished = false;

   private:
    std::array<Tick, kRing> ring_;
  };

  RunElastic(std::unique_ptr<ElasticModel> model, std::function<Status(const ElasticTick&)> on_tick,
             const ElasticIntegration& integration, const statics::LoadModel* load);
  /// The process load at tick `index`, travelling along `velocity_mm_s` (zero: at rest).
  statics::Wrench load_at(const Tick& tick, const Eigen::Vector3d& velocity_mm_s) const;
  Status begin(const Tick& first);
  Status report_until(long last_index);

  // On the heap: the simulator keeps the model's and the drives' addresses across moves of the run.
  std::unique_ptr<ElasticModel> model_;
  std::unique_ptr<TickHistory> history_;
  std::function<Status(const ElasticTick&)> on_tick_;
  const statics::LoadModel* load_ = nullptr;
  Eigen::Vector3d tool_axis_platform_ = Eigen::Vector3d::UnitZ();
  ElasticSimulator simulator_;
  long reported_ = 0;  ///< ticks reported
  ElasticRunSummary summary_;
};

}  // namespace pkm::dynamics
