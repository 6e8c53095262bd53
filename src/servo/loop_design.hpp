#pragma once
// The gains of each drive's cascade from the machine file's `servo:` section (motion-control textbook,
// §2.7.3, eq. 2.48–2.49, its printed errors corrected). Inner loop: the current loop as the equivalent
// lag k_μ/(T_μ p + 1), giving the force F = k_μ F_base u for the command u (per unit). Plant of one drive:
// the inertia a it moves, F = a ẇ (T0 = a w_base/F_base in per-unit form, W0 = 1/(T0 p)).
//   technical optimum: speed regulator T0/(2 k_μ T_μ) (P), so that the closed speed loop is
//     1/(2T_μ²p² + 2T_μp + 1) (2nd-order Butterworth, ω0 = 1/(√2 T_μ)); position regulator 1/(4T_μ) (P,
//     not written out in the textbook), so that the closed position loop is 1/(8T_μ³p³ + 8T_μ²p² + 4T_μp + 1)
//     (3rd-order Butterworth, ω0 = 1/(2T_μ)).
//   symmetric optimum: the same speed gain with an integral of time 4 T_μ (PI) and the speed reference
//     filtered by 1/(4T_μ p + 1); position gain 1/(8 T_μ) around it.
//   explicit: the file's gains.
// In physical units the speed regulator gives the force K_w (w_ref − w) with K_w = k_μ F_base K/w_base
// (= a/(2T_μ) under both optima).
#include <array>

#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm::servo {

/// One drive's loops in the actuator's units (mm or rad, N or N·mm, s): what the simulator runs.
struct ChannelGains {
  double lag_s = 0.0;                 ///< T_μ
  double force_per_command = 0.0;     ///< k_μ F_base: force for a unit command
  double command_max = 0.0;           ///< u_max k_μ F_base (∞: no clamp)
  double error_max = 0.0;             ///< e_max on the position error (∞: no clamp)
  double position_gain_per_s = 0.0;   ///< k_p: speed reference per unit position error
  double speed_gain = 0.0;            ///< K_w: force per unit speed error, N/(mm/s) (N·mm/(rad/s))
  double speed_integral_s = 0.0;      ///< T_i of the speed regulator's integral (0: P only)
  double reference_filter_s = 0.0;    ///< T_f of the speed reference's filter (0: none)
  double velocity_feedforward = 0.0;  ///< fraction of the set point's speed added to the speed reference
  double inertia = 0.0;               ///< a: the inertia the tuning assumed, N/(mm/s²) (N·mm/(rad/s²))
  /// The drive's imperfections (machine/servo_parameters.hpp), 0: none.
  double friction_coulomb = 0.0, friction_static = 0.0, stribeck_speed = 0.0, friction_viscous = 0.0;
  double backlash = 0.0;
  double encoder_resolution = 0.0;
  /// The static characteristic (servo_parameters.hpp) as (u, F in N or N·mm) points; 0 points: linear.
  std::array<std::array<double, 2>, DriveServo::kMaxCharacteristicPoints> characteristic{};
  int characteristic_points = 0;
};

/// The most loop periods a measurement may wait before the regulators act on it.
inline constexpr int kMaxSampleDelay = 8;

struct LoopDesign {
  ServoTuning tuning = ServoTuning::technical_optimum;
  int drives = 0;
  int sample_delay_periods = 0;  ///< ≤ kMaxSampleDelay
  std::array<ChannelGains, kMaxActuators> channels{};
};

/// The inertia of each drive's motor on its actuator coordinate, J_m · (motor rad per unit)², in
/// N/(mm/s²) (N·mm/(rad/s²) for angular actuators).
ActuatorVector motor_inertia(const ServoParameters& parameters, int drives);

/// The gains of every drive of `machine.servo`, tuned for `inertia` (each drive's own a_ii: its motor's and
/// the machine's on its coordinate). Fails, naming the machine file, the drive and its key, where an inertia
/// or a time constant is not positive.
Result<LoopDesign> design_loops(const Machine& machine, const ActuatorVector& inertia);

}  // namespace pkm::servo
