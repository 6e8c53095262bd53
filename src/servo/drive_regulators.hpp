#pragma once
// The regulating half of every drive's cascade (motion-control textbook, §2.7.4, Fig. 2.31), apart from the
// plant it acts on: every loop period each drive samples its motor's position and speed (through the
// encoder's counts and the sampling delay, when the drive has them), limits the position error to e_max,
// forms the speed reference k_p e (+ the set point's speed fed forward), filters it, and its speed regulator
// gives the force command K_w (e_w + ∫e_w/T_i), limited to u_max; the drive's static characteristic turns
// the command into the force its current loop settles on. The rigid plant (servo_simulator.hpp) and the
// elastic machine (coupled_machine.hpp) both close their loops through this.
//
// Never allocates; states are fixed-size.
#include <array>
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

/// The regulators' memory: what a stability analysis perturbs besides the plant.
struct RegulatorState {
  DriveVector integral = DriveVector::Zero();  ///< ∫ e_w dt of each speed regulator
  DriveVector filtered = DriveVector::Zero();  ///< the filtered speed reference
  /// The measurements waiting to be acted on, newest first.
  std::array<DriveVector, kMaxSampleDelay> delayed_position{}, delayed_speed{};
};

class DriveRegulators {
 public:
  DriveRegulators(const LoopDesign& design, double loop_period_s);

  /// At rest at `position`, each speed regulator's integral holding `holding_force` without a speed error.
  void reset(const DriveVector& position, const DriveVector& holding_force);

  /// One loop period: measures the motors at `position` moving at `speed`, regulates towards `reference`
  /// moving at `reference_speed`, and returns the force (N; N·mm) each current loop settles on.
  DriveVector regulate(const DriveVector& reference, const DriveVector& reference_speed,
                       const DriveVector& position, const DriveVector& speed);

  /// The force commands of the last period, per unit of k_μ F_base.
  const DriveVector& command() const { return command_; }
  const ClampFlags& clamps() const { return clamps_; }
  RegulatorState& state() { return state_; }
  const RegulatorState& state() const { return state_; }
  bool finite() const { return state_.integral.allFinite() && state_.filtered.allFinite(); }
  int drives() const { return drives_; }
  int sample_delay_periods() const { return delay_; }
  double loop_period_s() const { return period_s_; }

 private:
  void measure(const DriveVector& position, const DriveVector& speed, DriveVector& measured_position,
               DriveVector& measured_speed);

  int drives_;
  double period_s_;
  DriveVector position_gain_, speed_gain_, integral_gain_, filter_keep_, feedforward_;
  DriveVector error_max_, command_max_, force_per_command_, resolution_;
  bool encoder_ = false;
  int delay_ = 0;
  std::array<std::array<std::array<double, 2>, DriveServo::kMaxCharacteristicPoints>, kMaxActuators>
      characteristic_{};
  std::array<int, kMaxActuators> characteristic_points_{};
  DriveVector counted_ = DriveVector::Zero();  ///< the encoder's last position, whole counts
  RegulatorState state_;
  DriveVector command_ = DriveVector::Zero();
  ClampFlags clamps_;
};

}  // namespace pkm::servo
