#pragma once
// What the planned motion asks of the machine, measured on the servo-rate ticks themselves (not on the plan):
// actuator speeds and accelerations by finite differences at the servo rate, the path speed against the
// programmed feed, direction reversals of each actuator, and the path error: the distance of
// FK(actuators) from the programmed path, evaluated at mid-period, where the drives' straight-line motion
// between two setpoints deviates most from the curved actuator law (Smirnov 2019, §5.2.2–5.2.3).
#include <array>
#include <limits>
#include <memory>
#include <optional>

#include "core/rotation_angle.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::planning {

/// Relative excess of the path speed over the feed cap that is the rounding of the servo-rate samples, not
/// motion faster than programmed.
inline constexpr double kFeedRatioRounding = 1e-8;

/// What the run monitor measured on the ticks of a run (the analyses that listened report their own:
/// analyses/plan_analyses.hpp).
struct RunSummary {
  double duration_s = 0.0;
  long ticks = 0;
  double rate_hz = 0.0;
  double override_pct = 100.0;
  std::array<double, kMaxActuators> max_speed{};  ///< per actuator, unit/s (rad/s for angular actuators)
  std::array<double, kMaxActuators> max_accel{};
  std::array<int, kMaxActuators> reversals{};  ///< changes of direction of motion
  std::array<double, kMaxActuators> min_position{}, max_position{};
  double max_actuator_speed = 0.0;
  double max_actuator_accel = 0.0;
  int max_speed_line = 0, max_accel_line = 0;
  bool path_error_evaluated = false;  ///< false: --no-path-error, the errors below were not measured
  double max_path_error_mm = 0.0;     ///< perpendicular distance of the tool from the path
  int max_path_error_line = 0;
  double max_orientation_error_deg =
      0.0;                      ///< when the mechanism controls the orientation (all angles, or planar φ)
  double max_path_speed = 0.0;  ///< path units per second
  /// Path speed / (programmed feed × override, capped by the machine), ≤ 1: a ratio within
  /// kFeedRatioRounding of 1 counts as 1 (the jerk filter's sums round by about 1e-10), and within the
  /// rounding of the arc length itself, which grows with the distance travelled (run_monitor.cpp).
  double max_feed_ratio = 0.0;
  double max_path_accel = 0.0;  ///< path units per second², from the ticks
  double max_path_jerk = 0.0;
  Pose end_pose;
  int fk_failures = 0;
};

class RunMonitor {
 public:
  RunMonitor(const MotionPlan& plan, const Machine& machine, double override_pct, bool evaluate_path_error);
  void add(const ServoTick& tick);
  const RunSummary& summary() const { return summary_; }
  /// Of the tick added last: the path-speed cap from the programmed feed (path units/s) and the path error
  /// at its mid-period (mm; NaN for the first tick, when the error is not evaluated, or FK failed).
  double last_feed_cap() const { return last_feed_cap_; }
  double last_path_error_mm() const { return last_path_error_mm_; }
  /// Of the tick added last: the orientation error at its mid-period (deg; NaN where not evaluated, or where
  /// the mechanism does not control the whole orientation), and whether its forward kinematics failed.
  double last_orientation_error_deg() const;
  /// The orientation error of the tick added last above `bound` (false where not evaluated), without its arc
  /// tangent.
  bool last_orientation_error_exceeds(const RotationAngle& bound) const {
    return last_orientation_.exceeds(bound);
  }
  /// Of the tick added last: its actuator velocities and accelerations by finite differences (unit/s,
  /// unit/s²; zero where the ticks before it are too few), and its path speed over the feed cap.
  const ActuatorVector& last_velocity() const { return previous_velocity_; }
  const ActuatorVector& last_accel() const { return last_accel_; }
  double last_feed_ratio() const { return last_feed_ratio_; }
  bool last_fk_failed() const { return last_fk_failed_; }

 private:
  void add_feed_ratio(const ServoTick& tick);
  void add_path_error(const ServoTick& tick);
  void add_orientation_error(const Eigen::Matrix3d& actual, const Eigen::Matrix3d& on_path);
  const MotionPlan& plan_;
  const Machine& machine_;
  double override_factor_;
  bool evaluate_error_;
  RunSummary summary_;
  long count_ = 0;
  /// What the next tick needs of the one before (a whole tick is a few hundred bytes to copy every period).
  struct PreviousTick {
    ActuatorVector actuators;
    Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
    double s = 0.0;
    int segment = 0;
    double feed_cap = 0.0;  ///< of its segment
  };
  PreviousTick previous_;
  ActuatorVector previous_velocity_;
  std::array<int, kMaxActuators> direction_{};
  double previous_path_speed_ = 0.0, previous_path_accel_ = 0.0;
  Pose fk_guess_;
  /// The forward kinematics' state carried from tick to tick (the previous factorisation and the
  /// extrapolated start): the same continuation from the previous answer, without a fresh factorisation and a
  /// cold start every period.
  std::unique_ptr<FkWorkspace> fk_workspace_;
  FkSolution fk_solution_;
  double last_feed_cap_ = 0.0;
  double last_path_error_mm_ = std::numeric_limits<double>::quiet_NaN();
  /// The orientation error of the tick added last and the largest: compared without an arc tangent at
  /// every tick, in degrees only where asked or where it is a new maximum.
  RotationAngle last_orientation_{std::numeric_limits<double>::quiet_NaN(),
                                  std::numeric_limits<double>::quiet_NaN()};
  RotationAngle max_orientation_;
  ActuatorVector last_accel_;
  double last_feed_ratio_ = 0.0;
  bool last_fk_failed_ = false;
};

}  // namespace pkm::planning
