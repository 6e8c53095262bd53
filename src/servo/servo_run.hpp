#pragma once
// A planned run through the drives' servo loops (docs/servo.md): every drive's cascade
// (servo_simulator.hpp) follows the run's set points, interpolated linearly within each servo period as a
// drive in cyclic synchronous position mode does, on the plant of servo_plant.hpp. Per drive it measures the
// following error (set point − position at each servo tick), the force and the command and where the
// Fig. 2.31 limits acted; at the tool the contour error: the distance of FK(simulated positions) from the
// commanded tool path (the polyline of the run's commanded poses, at every tick and mid-period), and the lag
// behind it in time.
#include <array>
#include <functional>
#include <vector>

#include "servo/servo_plant.hpp"

namespace pkm::servo {

struct ServoRunOptions {
  /// The plant's inertia matrix in full (true), or only its diagonal: every drive an independent channel
  /// (the model the coupling check of textbook §2.7.1 justifies where the ratios are < 0.3).
  bool coupled = true;
};

/// One servo tick of the simulated run (pointers valid during the call only).
struct ServoTick {
  double time_s = 0.0;
  int line = 0;
  int drives = 0;
  const DriveVector* setpoint = nullptr;
  const DriveVector* position = nullptr;
  const DriveVector* force = nullptr;    ///< N (N·mm)
  const DriveVector* command = nullptr;  ///< per unit of k_μ F_base, the last loop step's
  double contour_error_mm = 0.0;         ///< NaN where FK failed
  double lag_s =
      0.0;            ///< how far behind the commanded path the tool is, in time (NaN where it nearly stands)
  ClampFlags clamps;  ///< the limits that acted in any loop step of the period
};

struct DriveServoSummary {
  double max_following_error = 0.0;  ///< mm (rad)
  double rms_following_error = 0.0;
  double max_following_time_s = 0.0;
  int max_following_line = 0;
  double peak_force = 0.0;          ///< N (N·mm)
  double peak_command = 0.0;        ///< per unit
  long error_clamps = 0;            ///< loop steps in which e_max acted
  long command_clamps = 0;          ///< loop steps in which u_max acted
  std::vector<int> clamp_lines;     ///< the program lines where a limit acted (ascending, at most 20)
  double max_coupling_ratio = 0.0;  ///< Σ_k |A'_ik| / J_m,i at its largest along the run
  int max_coupling_line = 0;
  std::vector<int> coupled_lines;  ///< program lines where the ratio is ≥ 0.3 (ascending, at most 20)
};

struct ServoSummary {
  int drives = 0;
  double period_s = 0.0;
  double loop_period_s = 0.0;
  bool coupled = true;
  bool has_machine_dynamics = false;
  std::array<DriveServoSummary, kMaxActuators> drive{};
  double max_contour_error_mm = 0.0;
  double rms_contour_error_mm = 0.0;
  double max_contour_time_s = 0.0;
  int max_contour_line = 0;
  double max_lag_s = 0.0;
  /// The program lines with the largest contour error, worst first (at most 10): line, error mm.
  std::vector<std::pair<int, double>> worst_lines;
  long ticks = 0;
  long fk_failures = 0;
};

/// The coupling ratio above which the drives cannot be treated as independent channels (textbook §2.7.1).
constexpr double kCouplingRatioLimit = 0.3;

/// The drives' loop period for a run at the servo period `period_s`: `servo.loop_period_ms`, or the servo
/// period itself. Fails, naming the machine file's key, unless it divides the servo period.
Result<int> loop_steps_per_period(const Machine& machine, double period_s);

/// Fails, naming the program line and the drive, where the closed loops are unstable on the plant of some
/// inertia sample (the spectral radius of the loop period's map, without the limits, reaches 1).
Status check_stability(const Machine& machine, const LoopDesign& design, const ServoPlant& plant,
                       const ServoRunInput& input, int steps_per_period, const ServoRunOptions& options);

/// Simulates the run; `on_tick` (may be empty) receives every servo tick in order. Fails where a state stops
/// being finite (never expected after check_stability) or on_tick fails.
Result<ServoSummary> run_servo(const Machine& machine, const LoopDesign& design, const ServoPlant& plant,
                               const ServoRunInput& input, int steps_per_period,
                               const ServoRunOptions& options,
                               const std::function<Status(const ServoTick&)>& on_tick = {});

}  // namespace pkm::servo
