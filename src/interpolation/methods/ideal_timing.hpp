#pragma once
// The interpolator's ideal time τ (Smirnov 2019, §5.2.2): the argument of the strut laws, parametrised at the
// nominal speed. Here the nominal motion is the planned one (planning/): s(τ) is the path parameter the plan
// reaches at time τ, with its acceleration, deceleration and S-curve, and within every actuator limit. The
// interpolator advances τ by K_V·h per real period (operator override, eq. 161), less where the chord check
// (eq. 155) or the drives' step rate ask for it, so real time t runs ahead of τ (t ≥ τ, t_0 = τ_0).
//
// s(τ) is kept at the plan's ticks and interpolated linearly between them: the contour error depends only on
// the geometry of the strut laws along the path, not on how fast s advances within one tick.
//
// For a plan made while it streams (planning/plan_producer.hpp) the timing is a window: ticks are appended as
// the plan reaches them and forgotten behind the interpolator, so its memory does not grow with the program.
#include <cstddef>
#include <limits>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"

namespace pkm::interpolation {

class IdealTiming {
 public:
  /// s at every tick of the planned motion (the servo stream of the plan, at the plan's period).
  static Result<IdealTiming> from_plan(const planning::MotionPlan& plan, const Machine& machine);
  /// Constant speed from the first instant to the end, no acceleration (the set-up of Smirnov 2019, §5.2.3).
  static IdealTiming constant_speed(double length, double speed_per_s);
  /// An open window at the plan's period: ticks come by append() until finish().
  static IdealTiming window(double period_s);

  /// The window's next tick (its s); until finish() the duration is unknown (infinite).
  void append(double s);
  /// The last tick appended is the path's end: `length` exactly. Fixes the duration.
  void finish(double length);
  bool finished() const { return finished_; }
  /// The ideal time of the last tick held (−1 before the first).
  double covered_s() const { return static_cast<double>(base_ + s_.size()) * period_s_ - period_s_; }
  /// The ticks held (a window's, or all).
  std::size_t held_ticks() const { return s_.size(); }
  /// Forgets the ticks before the interval containing τ (amortised O(1)).
  void drop_before(double tau_s);

  double duration_s() const { return duration_s_; }  ///< τ_Tr: the ideal time of the whole path
  double length() const { return length_; }
  /// s(τ), clamped to [0, τ_Tr]; s(τ_Tr) is exactly the path's length. No allocation.
  double s_at(double tau_s) const noexcept;
  /// The nominal path speed at τ (path units per second), from the tick interval containing τ.
  double speed_at(double tau_s) const noexcept;

 private:
  double period_s_ = 0.001;
  std::vector<double> s_;  ///< at τ = (base_ + k)·period_s (empty: constant speed)
  std::size_t base_ = 0;   ///< ticks forgotten before s_[0]
  bool finished_ = true;
  double speed_ = 0.0;       ///< constant-speed timing
  double duration_s_ = 0.0;  ///< infinite while an open window grows
  double length_ = 0.0;
};

}  // namespace pkm::interpolation
