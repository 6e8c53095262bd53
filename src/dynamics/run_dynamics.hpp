#pragma once
// Drive forces, power and energy along a run at the servo rate: the commanded poses of consecutive ticks give
// the platform's twist and its rate by central differences (the motion is jerk-limited and smooth at the
// servo period), rigid_dynamics gives the forces. One tick behind the stream: tick k is evaluated when tick
// k + 1 arrives (the first and the last at rest, where every run starts and ends), and handed on when tick
// k + 2 is, with the drive command its drive model needs (drive_model.hpp: u = P + τ Ṗ under a lag, Ṗ by the
// central difference of the forces).
#include <array>
#include <functional>

#include "core/tick_window.hpp"
#include "dynamics/rigid_dynamics.hpp"
#include "machine/machine.hpp"
#include "statics/load_model.hpp"

namespace pkm::dynamics {

/// The dynamics of one tick.
struct TickDynamics {
  double time_s = 0.0;
  int line = 0;
  DriveForces forces;
  ActuatorVector power_W;    ///< P_j · q̇_j per drive
  ActuatorVector command_N;  ///< the drive command u_j that gives forces.total (= it for ideal drives)
};

/// How a drive's energy is counted (as redundancy/law.hpp's accountings, per servo period): no recovery
/// Σ|P q̇| (a braking drive still draws), braking free Σ max(0, P q̇), recovery max(0, Σ P q̇) (braking drives
/// feed the others).
struct EnergyTotals {
  double no_recovery_J = 0.0;
  double braking_free_J = 0.0;
  double recovery_J = 0.0;
};

struct RunDynamicsSummary {
  int drives = 0;
  std::array<double, kMaxActuators> peak_force_N{};  ///< largest |P_j| (N·mm for angular drives)
  std::array<double, kMaxActuators> peak_force_time_s{};
  std::array<int, kMaxActuators> peak_force_line{};
  std::array<double, kMaxActuators> peak_static_N{};
  std::array<double, kMaxActuators> peak_dynamic_N{};
  std::array<double, kMaxActuators> peak_power_W{};
  double peak_total_power_W = 0.0;
  int peak_total_power_line = 0;
  EnergyTotals energy;
  long ticks = 0;
};

/// Whether the machine file gives the masses and inertias drive forces need (its `dynamics:` section); the
/// error names the file and the key.
Status require_dynamics_section(const Machine& machine);

class RunDynamics {
 public:
  /// `on_tick` receives every evaluated tick in order (e.g. to write forces.csv); it may be empty. `load`,
  /// when given, is the process load on the tool along the run (statics/load_model.hpp: the cutting force
  /// split along the direction of travel, the tool axis being the one that is the base z axis at home).
  RunDynamics(const Machine& machine, double period_s, std::function<Status(const TickDynamics&)> on_tick,
              const statics::LoadModel* load = nullptr);
  /// The next commanded pose (`cutting`: false on rapids, where no cutting load acts); fails where the forces
  /// cannot be computed, or exceed the machine's actuator_force_max (the error's location holds the program
  /// line, the message the machine file's line).
  Status add(double time_s, int line, const Pose& pose, bool cutting = true);
  /// Evaluates the last tick (at rest) and hands on the last two; call once after the last add().
  Status finish();
  const RunDynamicsSummary& summary() const { return summary_; }

 private:
  Status evaluate(int index_in_window, bool at_rest);
  /// Hands on the pending tick with its command, Ṗ from the ticks either side (one side at the ends).
  Status hand_on(const TickDynamics* next);

  const Machine& machine_;
  double period_s_;
  std::function<Status(const TickDynamics&)> on_tick_;
  const statics::LoadModel* load_;
  Eigen::Vector3d tool_axis_platform_;
  using Sample = CommandedTick;
  TickWindow<Sample> window_;
  RunDynamicsSummary summary_;
  TickDynamics pending_;  ///< evaluated, waiting for the next tick's forces
  bool has_pending_ = false;
  double handed_time_s_ = 0.0;  ///< the tick handed on last (before pending_)
  ActuatorVector handed_force_N_;
  bool has_handed_ = false;
};

}  // namespace pkm::dynamics
