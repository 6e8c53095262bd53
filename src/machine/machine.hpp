#pragma once
// A machine: its mechanism plus what the machine file says about limits and where it came from.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "machine/dynamics_parameters.hpp"
#include "machine/mass_properties.hpp"
#include "machine/mechanism.hpp"
#include "machine/servo_parameters.hpp"
#include "machine/stiffness_parameters.hpp"

namespace pkm {

/// Actuator limits from the machine file. Lengths in mm (angular actuators: rad), speeds per s, accelerations
/// per s². `*_line` is the line of the key in the machine file, for messages (0 = not given).
struct ActuatorLimits {
  std::optional<double> min;
  std::optional<double> max;
  std::optional<double> speed;
  std::optional<double> accel;
  /// Largest force a drive can give, N (`actuator_force_max`; dynamics checks it).
  std::optional<double> force_N;
  int min_line = 0;
  int max_line = 0;
  int speed_line = 0;
  int accel_line = 0;
  int force_line = 0;
};

/// Passive-joint and conditioning limits from `limits:` (docs/machine-file.md); `*_line` as ActuatorLimits.
struct JointLimits {
  std::optional<double> base_joint_max_rad;      ///< largest swing of a base-side passive joint
  std::optional<double> platform_joint_max_rad;  ///< largest swing of a platform-side passive joint
  /// Largest condition number σ_max/σ_min of the actuator Jacobian (as jacobian_measures: mm and rad).
  std::optional<double> max_condition_number;
  int base_joint_max_line = 0;
  int platform_joint_max_line = 0;
  int max_condition_number_line = 0;
  /// cos of the two angle limits (−2 when not given): the check at every planning sample then compares
  /// cosines and needs no trigonometry. The loader sets them; call update_cosines() after changing a limit.
  double base_joint_min_cos = -2.0;
  double platform_joint_min_cos = -2.0;
  void update_cosines();
};

/// Neutral axes of the passive joints: per strut, the strut direction (base joint → platform joint, unit) at
/// which each of its two joints is centred. Base axes are in the joint's mount frame (the base frame, except
/// for joints on turning carriages: StrutJointPoints), platform axes in the platform frame. From the file's
/// `base_joint_axes` / `platform_joint_axes`, by default the strut directions at home (joints are mounted
/// centred at home).
struct PassiveJointAxes {
  int count = 0;  ///< struts with passive swing joints (0: none, e.g. planar pin joints)
  std::array<Eigen::Vector3d, kMaxActuators> base;
  std::array<Eigen::Vector3d, kMaxActuators> platform;
  int base_line = 0;      ///< line of `base_joint_axes` (0 = home default)
  int platform_line = 0;  ///< line of `platform_joint_axes` (0 = home default)
};

/// Path-motion settings from the machine file's `motion:` section (docs/machine-file.md).
// One field per line with aligned comments; clang-format would wrap the origin line.
// clang-format off
struct MotionSettings {
  double rapid_mm_min = 6000.0;       ///< speed of G0 moves along the path
  double max_feed_mm_min = 6000.0;    ///< programmed feeds are capped here
  double path_accel_mm_s2 = 1000.0;   ///< tangential (path) acceleration limit
  double path_jerk_mm_s3 = 20000.0;   ///< tangential (path) jerk limit
  double path_tolerance_mm = 0.01;    ///< corner blending: largest deviation from the programmed path
  double angular_feed_deg_min = 3600.0; ///< speed of moves that only rotate (no tool-point motion)
  Eigen::Vector3d program_origin_mm = Eigen::Vector3d::Zero(); ///< where program X0 Y0 Z0 is in the base frame
  int line = 0;                       ///< line of `motion:` in the file, for messages (0 = defaults)
};
// clang-format on

/// What the actuators' drives can do, from the machine file's `drives:` section (docs/machine-file.md).
/// Every value is optional; `pkm interpolate` options override them.
struct DriveSettings {
  std::optional<double> step;              ///< drive resolution Δ: mm per step (deg for angular actuators)
  std::optional<double> max_step_rate_hz;  ///< largest step rate of one drive
  std::optional<double> period_ms;         ///< servo (carrier) period h
  int line = 0;                            ///< line of `drives:` in the file, for messages (0 = not given)
};

struct Machine {
  std::string source;  ///< file the machine came from
  std::string name;
  std::unique_ptr<Mechanism> mechanism;
  ActuatorLimits limits;
  JointLimits joint_limits;
  PassiveJointAxes joint_axes;
  MotionSettings motion;
  MassProperties masses;          ///< `masses:` (machine/mass_properties.hpp); no masses by default
  DynamicsParameters dynamics;    ///< `dynamics:` (machine/dynamics_parameters.hpp); not given by default
  StiffnessParameters stiffness;  ///< `stiffness:` (machine/stiffness_parameters.hpp); not given by default
  ServoParameters servo;          ///< `servo:` (machine/servo_parameters.hpp); not given by default
  DriveSettings drives;
  bool home_given = false;
};

/// Checks actuator positions against the machine's range; the error names the actuator, the value, the limit,
/// and the machine file line that set it.
Status check_actuator_range(const Machine& machine, const ActuatorVector& actuators);

}  // namespace pkm
