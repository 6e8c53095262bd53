#pragma once
// All drives' cascades in discrete time on the rigid plant (motion-control textbook, §2.7.4, Fig. 2.31):
// every loop period h the regulators of drive_regulators.hpp sample each drive's position q and speed w and
// give its force command, held over the period (zero-order hold). Each limit that acts is flagged for the
// protection-and-diagnostics system.
//
// Plant, with the command held: each drive's current loop is the lag T_μ Ḟ + F = F_cmd, and the machine is
// A ẇ = F − d (eq. 2.43: A the inertia matrix in actuator coordinates, Coriolis terms neglected as §2.7.1
// argues; d the load the drives must carry: gravity, the process load and the velocity terms of the planned
// motion). With A and d constant over a step, the step is integrated exactly (the lag's closed form and its
// first two integrals), in two halves so that the state at mid-period is known too.
//
// The drives' imperfections (docs/servo.md, "Drive imperfections"), each off where its value is 0:
//   sampling delay   the regulators act on the positions and speeds sampled d loop periods before;
//   encoder          the position is measured in whole counts of the motor's encoder, and the speed as the
//                    counts' difference over the loop period;
//   friction         F_f = sign(w)·(F_c + (F_s − F_c)·e^(−(w/w_s)²)) + b·w on each actuator; a drive at rest
//                    sticks while the force on it is within F_s (Karnopp). The plant then advances in eight
//                    sub-steps per half period with the friction held over each, and a drive whose speed
//                    friction would reverse stops instead;
//   backlash         the actuator follows the motor through a gap of width b_l (the motor's side carries the
//                    encoder): it stays where it is until the motor has crossed the gap;
//   characteristic   the current loop settles on the force of the drive's static characteristic for the
//                    command, F = f(u) (piecewise linear, odd), instead of k_μ F_base u.
//
// The hot path: step() neither allocates nor branches on the mechanism; states are fixed-size.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "servo/drive_regulators.hpp"

namespace pkm::servo {

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
  /// The motors' positions (on the actuator coordinate), and the actuators' (the motors' less the backlash
  /// they have not taken up; the same without backlash), at the end and the middle of the last step.
  const DriveVector& position() const { return position_; }
  const DriveVector& actuator_position() const { return actuator_; }
  const DriveVector& mid_actuator_position() const { return mid_actuator_; }
  const DriveVector& speed() const { return speed_; }
  const DriveVector& force() const { return force_; }
  /// The positions at the middle of the last step.
  const DriveVector& mid_position() const { return mid_position_; }
  /// The force commands of the last step, in units of k_μ F_base (the per-unit command u).
  const DriveVector& command() const { return regulators_.command(); }
  const ClampFlags& clamps() const { return regulators_.clamps(); }
  /// Every state (positions, speeds, forces, speed integrals, filtered references, then the delayed
  /// positions and speeds, newest first), for the stability check.
  static constexpr int kStateSize = (5 + 2 * kMaxSampleDelay) * kMaxActuators;
  /// Where the delayed samples start in the state, and the stride between their ages.
  static constexpr int kDelayedPositionState = 5 * kMaxActuators;
  static constexpr int kDelayedSpeedState = (5 + kMaxSampleDelay) * kMaxActuators;
  using StateVector = Eigen::Matrix<double, kStateSize, 1>;
  StateVector state() const;
  void set_state(const StateVector& state);
  /// False once a state is no longer finite (an unstable loop); the states are then meaningless.
  bool finite() const;

 private:
  // The plant's lag over a time step: F's closed form and its first two integrals (see the .cpp).
  struct LagStep {
    double duration_s = 0.0;
    DriveVector keep = DriveVector::Zero(), first = DriveVector::Zero(), second = DriveVector::Zero();
  };
  static LagStep lag_step(const LoopDesign& design, double duration_s);
  void advance(const DriveVector& force_command, const DriveVector& load, const LagStep& step);
  void advance_plant(const DriveVector& force_command);
  void advance_with_friction(const DriveVector& force_command);
  DriveVector friction_on(const DriveVector& speed, const DriveVector& net_force, std::uint32_t& stuck) const;
  void take_up_backlash(DriveVector& actuator) const;

  int drives_;
  double period_s_;
  double half_s_;
  DriveRegulators regulators_;
  // The lag's closed form over a half step (α = e^(−h/2T_μ), c1, c2) and over a friction sub-step.
  LagStep half_step_, sub_step_;
  // The plant's imperfections (0: none), per drive.
  DriveVector coulomb_, static_friction_, stribeck_, viscous_, backlash_;
  bool friction_ = false, backlash_on_ = false;
  DriveVector actuator_ = DriveVector::Zero(), mid_actuator_ = DriveVector::Zero();
  DriveMatrix inverse_inertia_ = DriveMatrix::Zero();
  DriveVector load_ = DriveVector::Zero();
  DriveVector position_ = DriveVector::Zero(), speed_ = DriveVector::Zero(), force_ = DriveVector::Zero();
  DriveVector mid_position_ = DriveVector::Zero();
};

}  // namespace pkm::servo
