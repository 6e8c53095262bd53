#pragma once
// Time integration of the elastic machine (elastic_model.hpp) under kinematic excitation (spec ch4 §4.4,
// §6.7): the drives' positions q(t) and rates q̇(t) are given, the platform's pose and twist coordinates are
// integrated. Boost.Odeint's Dormand–Prince 5(4) with step-size control (the seed names no integrator, no
// step and no tolerance: errata 21, so both tolerances are parameters here).
//
// The state is the pose and the coordinate rates, the rotation integrated as a rotation: a unit quaternion
// with q̇ = ½ (0, ω) ⊗ q, the quaternion form of Ṙ = [ω]× R, never Euler angles (no small-angle assumption,
// no angle singularity). So that one absolute and one relative tolerance make sense for every component, all
// are lengths: the tool point's displacement from the start (mm), the quaternion times the platform's size
// L (Mechanism::platform_size_mm: a rotation error ε then moves a platform joint ≈ ε·L), and each rate times
// a time scale τ (and times L for angular rates: the distance it covers in τ). τ defaults to 1/ω of the
// fastest vibration at the start, so a rate error counts as much as the position error it makes within a
// radian of that vibration.
//
// Integrating never allocates after start(); the right-hand side runs 6 times per accepted step (FSAL).
#include <memory>

#include "dynamics/elastic_model.hpp"

namespace pkm::dynamics {

/// The drives' motion: q_j(t) (mm) and q̇_j(t) (mm/s). Implementations are called from inside the
/// integrator's steps at any time within the interval being advanced over; they must not allocate.
class DriveMotion {
 public:
  virtual ~DriveMotion() = default;
  virtual void setpoint(double time_s, DriveSetpoint& out) const = 0;
};

/// Drives that hold their positions (free vibration, spec ch4 §8.5 test 3).
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

struct ElasticIntegration {
  /// Absolute tolerance of each length-scaled state component (see above), mm.
  double abs_tolerance_mm = 1e-7;
  /// Relative tolerance of each component.
  double rel_tolerance = 1e-9;
  /// τ of the rates' scaling, s; 0: 1/ω_max at the start pose (from the material stiffness).
  double rate_time_scale_s = 0.0;
  /// Longest step, s (0: no limit). Steps run past the time asked for by up to this much (the state there
  /// is interpolated), so drives known only up to some time need it (RunElastic: the servo period).
  double max_step_s = 0.0;
  /// Steps one advance_to() may take before it gives up.
  long max_steps_per_advance = 5'000'000;
};

/// Counters of the integration, for tests and the benchmark.
struct IntegrationCounters {
  long accepted_steps = 0;
  long evaluations =
      0;  ///< right-hand side evaluations (6 per accepted or rejected step, first same as last)
};

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
