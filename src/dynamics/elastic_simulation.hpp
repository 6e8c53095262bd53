#pragma once
// Time integration of the elastic machine (elastic_model.hpp) under kinematic excitation (Smirnov 2019,
// §4.5): the drives' positions q(t) and rates q̇(t) are given, the platform's pose and twist coordinates are
// integrated by platform_integrator.hpp, whose rate time scale τ defaults here to 1/ω of the fastest
// vibration at the start, so a rate error counts as much as the position error it makes within a radian of
// that vibration.
#include <memory>

#include "dynamics/elastic_model.hpp"
#include "dynamics/platform_integrator.hpp"

namespace pkm::dynamics {

/// The drives' motion: q_j(t) (mm) and q̇_j(t) (mm/s). Implementations are called from inside the
/// integrator's steps at any time within the interval being advanced over; they must not allocate.
class DriveMotion {
 public:
  virtual ~DriveMotion() = default;
  virtual void setpoint(double time_s, DriveSetpoint& out) const = 0;
};

/// Drives that hold their positions (free vibration).
class HeldDrives final : public DriveMotion {
 public:
  explicit HeldDrives(const ActuatorVector& position_mm)
      : position_mm_(position_mm), rate_mm_s_(ActuatorVector::Zero(position_mm.size())) {}
  void setpoint(double, DriveSetpoint& out) const override {
    out.position_mm = position_mm_;
    out.rate_mm_s = rate_mm_s_;
  }

 private:
  ActuatorVector position_mm_;
  ActuatorVector rate_mm_s_;
};

/// The integrator's settings; rate_time_scale_s 0 means 1/ω_max at the start pose.
using ElasticIntegration = PlatformIntegration;

class ElasticSimulator {
 public:
  /// The model (and the machine it refers to) must outlive the simulator. Allocates its integrator once.
  ElasticSimulator(const ElasticModel& model, const ElasticIntegration& integration = {});
  ~ElasticSimulator();
  ElasticSimulator(ElasticSimulator&&) noexcept;
  ElasticSimulator& operator=(ElasticSimulator&&) noexcept;

  /// Starts at `time_s` from a complete pose moving with coordinate rates `rates` (mm/s, rad/s in the
  /// model's basis). Fails where the pose is out of reach or has no positive-definite mass matrix.
  Status start(double time_s, const Pose& pose, const CoordinateVector& rates);
  /// Integrates until the state at `time_s` (≥ the last) is known and makes it the current one. Steps start
  /// before `time_s` and may end past it (by at most max_step_s, when set): the drives must be defined
  /// there; the state at `time_s` is Dormand–Prince's dense output within the step. A DriveMotion object used
  /// again by the next call must agree with what it said before for the times already stepped over (the
  /// steps taken are kept); a different object restarts the stepper at the current state. Fails where the
  /// platform leaves the mechanism's reach or the step size collapses.
  Status advance_to(double time_s, const DriveMotion& drives);

  double time_s() const;
  /// The platform's pose (rotation re-orthonormalised from the quaternion) and coordinate rates now.
  Pose pose() const;
  CoordinateVector rates() const;
  const IntegrationCounters& counters() const;
  /// τ in use (s).
  double rate_time_scale_s() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::dynamics
