#pragma once
// What the machine file's `servo:` section says about the drives' control loops (docs/machine-file.md,
// docs/servo.md; motion-control textbook, §2.7): per drive the current loop as the equivalent
// first-order lag k_μ/(T_μ p + 1) of eq. (2.49)'s derivation, the base speed and force of the per-unit form
// (T0 = w_base/F_base · a), the motor's inertia and its transmission to the actuator coordinate, the clamps
// of the Fig. 2.31 algorithm (e_max on the position error, u_max on the force command), and how the speed and
// position loops are tuned.
//
// Units: linear actuators in mm, mm/s and N; angular actuators (e.g. rotopods) in rad, rad/s and N·mm inside
// (the file gives degrees and N·mm). Motor inertia kg·cm² as motor catalogues give it.
#include <array>
#include <limits>

#include "machine/mechanism.hpp"

namespace pkm {

/// How the speed and position loops are tuned (motion-control textbook, §2.7.3).
enum class ServoTuning {
  /// Speed loop P with gain T0/(2 k_μ T_μ) (closed: 1/(2T_μ²p² + 2T_μp + 1), 2nd-order Butterworth), position
  /// loop P with gain 1/(4 T_μ) (closed: 1/(8T_μ³p³ + 8T_μ²p² + 4T_μp + 1), 3rd-order Butterworth).
  technical_optimum,
  /// Speed loop PI, the same proportional gain and integral time 4 T_μ, its set point filtered by
  /// 1/(4 T_μ p + 1): no static speed error under a constant load (gravity, the cutting force); position loop
  /// P with gain 1/(8 T_μ).
  symmetric_optimum,
  /// The gains as the file gives them.
  explicit_gains,
};

const char* to_string(ServoTuning tuning);

/// One drive's loops.
struct DriveServo {
  double current_time_constant_s = 0.0;  ///< T_μ of the current (force) loop
  double current_gain = 1.0;             ///< k_μ: force per unit command, in units of base_force
  double base_speed = 0.0;               ///< w_base, mm/s (rad/s)
  double base_force = 0.0;               ///< F_base, N (N·mm)
  double motor_inertia_kg_mm2 = 0.0;     ///< J_m on the motor shaft
  /// Motor radians per actuator unit: 2π/lead (rad/mm) for a screw, the gear ratio for an angular actuator;
  /// the motor's inertia reflected onto the actuator coordinate is J_m · ratio².
  double motor_rad_per_unit = 0.0;
  double error_max = std::numeric_limits<double>::infinity();    ///< e_max on the position error, mm (rad)
  double command_max = std::numeric_limits<double>::infinity();  ///< u_max, in units of base_force
  /// explicit_gains only: position gain (1/s), speed gain (per unit command per unit speed error), speed
  /// integral time (s; 0 = none).
  double position_gain_per_s = 0.0;
  double speed_gain = 0.0;
  double speed_integral_s = 0.0;
  /// The drive's imperfections (docs/servo.md, "Drive imperfections"), 0 where not given. Friction on the
  /// actuator coordinate, N (N·mm): Coulomb F_c, static (breakaway) F_s ≥ F_c falling to F_c over the
  /// Stribeck speed w_s, viscous b in N per mm/s (N·mm per rad/s).
  double friction_coulomb = 0.0;
  double friction_static = 0.0;
  double stribeck_speed = 0.0;  ///< mm/s (rad/s)
  double friction_viscous = 0.0;
  double backlash = 0.0;            ///< lost motion between the motor and the actuator, mm (rad)
  double encoder_resolution = 0.0;  ///< one count of the motor's encoder, mm (rad)
  /// The axial stiffness of the transmission between the motor and the strut (screw, nut, bearings, belt),
  /// N/mm (N·mm/rad); in series with the strut's own stiffness in the elastic machine (0: rigid).
  double transmission_stiffness = 0.0;
  /// The transmission's viscous damping in parallel with its stiffness, N·s/mm (N·mm·s/rad).
  double transmission_damping = 0.0;
  /// The drive's static characteristic: the steady force for a command, as points (u, F/F_base) from (0, 0)
  /// with u rising and F not falling, the same for −u (odd); past the last point F stays (saturation). None
  /// given (0 points): F = k_μ F_base u.
  static constexpr int kMaxCharacteristicPoints = 16;
  std::array<std::array<double, 2>, kMaxCharacteristicPoints> characteristic{};
  int characteristic_points = 0;
  /// Lines of the keys in the machine file, for messages (0 = not given).
  int line = 0;
  int time_constant_line = 0;
  int position_gain_line = 0;
  int speed_gain_line = 0;
};

struct ServoParameters {
  ServoTuning tuning = ServoTuning::technical_optimum;
  /// The period of the drives' own speed and position loops, s (0: the servo period drives.period_ms). The
  /// drive interpolates the CNC's set points linearly within each servo period, as drives in cyclic
  /// synchronous position mode do.
  double loop_period_s = 0.0;
  /// Fraction (0…1) of the set point's speed fed forward into the speed loop's reference (0 in the
  /// textbook: the ramp's following error is then 4 T_μ v under the technical optimum).
  double velocity_feedforward = 0.0;
  /// Loop periods between sampling the drives' positions and speeds and acting on them (0 … 8).
  int sample_delay_periods = 0;
  int drive_count = 0;
  std::array<DriveServo, kMaxActuators> drives{};
  int line = 0;  ///< line of `servo:` in the file (0 = no servo section)
  int tuning_line = 0;
  int loop_period_line = 0;
  bool given() const { return line > 0; }
};

}  // namespace pkm
