#pragma once
// The interpolator's ideal time τ (Smirnov 2019, §5.2.2): the argument of the strut laws, parametrised at the
// nominal speed. Here the nominal motion is the planned one (planning/): s(τ) is the path parameter the plan
// reaches at time τ, with its acceleration, deceleration and S-curve, and within every actuator limit. The
// interpolator advances τ by K_V·h per real period (operator override, eq. 161), less where the chord check
// (eq. 155) or the drives' step rate ask for it, so real time t runs ahead of τ (t ≥ τ, t_0 = τ_0).
//
// s(τ) is kept at the plan's ticks and interpolated linearly between them: the contour error depends only on
// the geometry of the strut laws along the path, not on how fast s advances within one tick.
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

  double duration_s() const { return duration_s_; }  ///< τ_Tr: the ideal time of the whole path
  double length() const { return length_; }
  /// s(τ), clamped to [0, τ_Tr]; s(τ_Tr) is exactly the path's length. No allocation.
  double s_at(double tau_s) const noexcept;
  /// The nominal path speed at τ (path units per second), from the tick interval containing τ.
  double speed_at(double tau_s) const noexcept;

 private:
  double period_s_ = 0.001;
  std::vector<double> s_;  ///< at τ = k·period_s (empty: constant speed)
  double speed_ = 0.0;     ///< constant-speed timing
  double duration_s_ = 0.0;
  double length_ = 0.0;
};

}  // namespace pkm::interpolation
