#pragma once
// All drives' cascades in discrete time (motion-control textbook, §2.7.4, Fig. 2.31): every loop
// period h each drive samples its position q and speed w, limits the position error to e_max, forms the
// speed reference k_p e (+ the set point's speed fed forward), filters it (symmetric optimum), and its
// speed regulator gives the force command K_w (e_w + ∫e_w/T_i), limited to u_max; the command is held over
// the period (zero-order hold). Each limit that acts is flagged for the protection-and-diagnostics system.
//
// Plant, with the command held: each drive's current loop is the lag T_μ Ḟ + F = F_cmd, and the machine is
// A ẇ = F − d (eq. 2.43: A the inertia matrix in actuator coordinates, Coriolis terms neglected as §2.7.1
// argues; d the load the drives must carry: gravity, the process load and the velocity terms of the planned
// motion). With A and d constant over a step, the step is integrated exactly (the lag's closed form and its
// first two integrals), in two halves so that the state at mid-period is known too.
//
// The hot path: step() neither allocates nor branches on the mechanism; states are fixed-size.
#include <Eigen/Core>
#include <cstdint>

#include "servo/loop_design.hpp"

namespace pkm::servo {

using DriveVector = Eigen::Matrix<double, kMaxActuators, 1>;
using DriveMatrix = Eigen::Matrix<double, kMaxActuators, kMaxActuators>;

/// What the limits did in the last step, one bit per drive.
struct ClampFlags {
  std::uint32_t error = 0;    ///< |e| > e_max: the position error was limited
  std::uint32_t command = 0;  ///< |u| > u_max: the force command was limited
};

class ServoSimulator {
 public:
  /// `loop_period_s` > 0. The inertia starts as the tuning's own (diagonal), the load at zero.
  ServoSimulator(const LoopDesign& design, double loop_period_s);

  /// The inverse of the inertia matrix A the drives move (drives × drives, the rest zero).
  void set_inverse_inertia(const DriveMatrix& inverse_inertia) { inverse_inertia_ = inverse_inertia; }
  /// The load d the drives carry (N; N·mm), held until changed.
  void set_load(const DriveVector& load) { load_ = load; }
  /// At rest at `position`, each drive giving the force that holds the current load.
  void reset(const DriveVector& position);

  /// One loop period: the regulators sample the state against the set point `reference` moving at
  /// `reference_speed`, and the plant advances by h under the held commands.
  void step(const DriveVector& reference, const DriveVector& reference_speed);

  double loop_period_s() const { return period_s_; }
  const DriveVector& position() const { return position_; }
  const DriveVector& speed() const { return speed_; }
  const DriveVector& force() const { return force_; }
  /// The positions at the middle of the last step.
  const DriveVector& mid_position() const { return mid_position_; }
  /// The force commands of the last step, in units of k_μ F_base (the per-unit command u).
  const DriveVector& command() const { return command_; }
  const ClampFlags& clamps() const { return clamps_; }
  /// Every state (positions, speeds, forces, speed integrals, filtered references), for the stability check.
  static constexpr int kStateSize = 5 * kMaxActuators;
  using StateVector = Eigen::Matrix<double, kStateSize, 1>;
  StateVector state() const;
  void set_state(const StateVector& state);
  /// False once a state is no longer finite (an unstable loop); the states are then meaningless.
  bool finite() const;

 private:
  void advance_plant(const DriveVector& force_command);

  int drives_;
  double period_s_;
  double half_s_;
  // Per drive: gains, and the lag's closed form over a half step (α = e^(−h/2T_μ), c1, c2).
  DriveVector position_gain_, speed_gain_, integral_gain_, filter_keep_, feedforward_;
  DriveVector error_max_, command_max_, force_per_command_;
  DriveVector lag_keep_, lag_first_, lag_second_;
  DriveMatrix inverse_inertia_ = DriveMatrix::Zero();
  DriveVector load_ = DriveVector::Zero();
  DriveVector position_ = DriveVector::Zero(), speed_ = DriveVector::Zero(), force_ = DriveVector::Zero();
  DriveVector integral_ = DriveVector::Zero(), filtered_ = DriveVector::Zero();
  DriveVector mid_position_ = DriveVector::Zero(), command_ = DriveVector::Zero();
  ClampFlags clamps_;
};

}  // namespace pkm::servo
