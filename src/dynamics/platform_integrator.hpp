#pragma once
// Time integration of a free platform (free_platform.hpp): its pose and basis-coordinate rates, plus up to
// twenty auxiliary states of the model driving it (the drives' forces under a first-order lag; the drives'
// positions, speeds and forces of the machine in the servo loops). Boost.Odeint's
// Dormand–Prince 5(4) with step-size control by a PI controller (pi_step_adjuster.hpp; Smirnov 2019 names no
// integrator, no step and no tolerance, so both tolerances are parameters here).
//
// The rotation is integrated as a rotation: a unit quaternion with q̇ = ½ (0, ω) ⊗ q, the quaternion form of
// Ṙ = [ω]× R, never Euler angles (no small-angle assumption, no angle singularity). So that one absolute and
// one relative tolerance make sense for every component, all are lengths: the tool point's displacement from
// the start (mm), the quaternion times the platform's size L (Mechanism::platform_size_mm: a rotation error
// ε then moves a platform joint ≈ ε·L), each rate times a time scale τ (and times L for angular rates: the
// distance it covers in τ), and each auxiliary state times the length its model says one unit of it is
// worth.
//
// Integrating never allocates after start(); the right-hand side runs 6 times per accepted step (FSAL).
#include <memory>
#include <string>

#include "dynamics/free_platform.hpp"

namespace pkm::dynamics {

/// The most auxiliary states a model may have: each of six drives' position, speed and force, and two
/// energy accounts.
inline constexpr int kMaxAuxiliaryStates = 20;
/// The auxiliary states of a model.
using AuxiliaryVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxAuxiliaryStates, 1>;

struct PlatformIntegration {
  /// Absolute tolerance of each length-scaled state component (see above), mm.
  double abs_tolerance_mm = 1e-7;
  /// Relative tolerance of each component.
  double rel_tolerance = 1e-9;
  /// τ of the rates' scaling, s; 0: the model's own (ElasticSimulator: 1/ω_max at the start pose).
  double rate_time_scale_s = 0.0;
  /// Longest step, s (0: no limit). Steps run past the time asked for by up to this much (the state there
  /// is interpolated), so inputs known only up to some time need it (RunElastic: the servo period).
  double max_step_s = 0.0;
  /// Steps one advance_to() may take before it gives up.
  long max_steps_per_advance = 5'000'000;
};

/// Counters of the integration, for tests and the benchmark.
struct IntegrationCounters {
  long accepted_steps = 0;
  /// Right-hand side evaluations (6 per accepted or rejected step, first same as last).
  long evaluations = 0;
};

/// The model's equations: the coordinate accelerations and the auxiliary states' rates at an instant.
class PlatformRightHandSide {
 public:
  virtual ~PlatformRightHandSide() = default;
  /// Called from inside the integrator's steps at any time within the interval being advanced over; must
  /// not allocate. A failure (the pose out of reach) stops the integration and is reported.
  virtual Status evaluate(double time_s, const Pose& pose, const CoordinateVector& rates,
                          const AuxiliaryVector& auxiliary, CoordinateVector& accelerations,
                          AuxiliaryVector& auxiliary_rates) = 0;
};

/// How the state's components are made lengths (see above).
struct PlatformScales {
  double length_mm = 1.0;     ///< L
  double time_scale_s = 0.0;  ///< τ
  /// Per auxiliary state: mm per unit.
  AuxiliaryVector auxiliary_mm_per_unit;
};

class PlatformIntegrator {
 public:
  /// `name` prefixes error messages ("elastic simulation"). The model must outlive the integrator.
  PlatformIntegrator(const FreePlatformModel& model, const PlatformIntegration& integration,
                     const char* name);
  ~PlatformIntegrator();
  PlatformIntegrator(PlatformIntegrator&&) noexcept;
  PlatformIntegrator& operator=(PlatformIntegrator&&) noexcept;

  /// Starts at `time_s` from a complete pose with coordinate rates and auxiliary states (as many as
  /// scales.auxiliary_mm_per_unit has entries).
  void start(double time_s, const Pose& pose, const CoordinateVector& rates, const AuxiliaryVector& auxiliary,
             const PlatformScales& scales);
  /// Restarts the stepper at the current state (a new right-hand side: no derivative of the old one to reuse,
  /// and no step taken under it past now).
  void restart();
  /// Integrates until the state at `time_s` (≥ the last) is known and makes it the current one. Steps start
  /// before `time_s` and may end past it (by at most max_step_s, when set); the state at `time_s` is
  /// Dormand–Prince's dense output within the step. Fails where the right-hand side fails or the step size
  /// collapses.
  Status advance_to(double time_s, PlatformRightHandSide& equations);
  /// The same, but no step ends past `time_s` (the last one is shortened onto it), so that the right-hand
  /// side may change there (a command held over a loop period); the stepper restarts at `time_s`.
  Status advance_exactly_to(double time_s, PlatformRightHandSide& equations);

  double time_s() const;
  Pose pose() const;
  CoordinateVector rates() const;
  AuxiliaryVector auxiliary() const;
  const IntegrationCounters& counters() const;
  const PlatformScales& scales() const;

  struct Impl;

 private:
  const FreePlatformModel* model_;
  PlatformIntegration integration_;
  std::string name_;
  bool large_ = false;  // the state holds kMaxAuxiliaryStates auxiliary states (else six)
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::dynamics
