#pragma once
// Interpolation at a constant carrier frequency (Smirnov 2019, §5.2.2, and its pipeline). Every real period
// h the interpolator advances the ideal time τ and gives each actuator's ideal value at the period's end from
// the strut laws L_j(s(τ)); the drives then run at constant speed through the period (linear in the
// actuator values, the chords of Fig. 157), and quantisation (step_quantizer.hpp) turns the increments into
// whole steps.
//
// Per period:
//  1. Δτ = K_V·h, the operator override from period i+2 (feed_override.hpp, eq. 161, 165);
//  2. chord check (eq. 154, 155): the mid-period deviation of every strut's chord from its law,
//       ΔL_max = L(s_mid) − (L(s_0) + L(s_1))/2 ≤ ΔL_allowed = 0.9·ρ_max/δρ_max,
//     measured at the geometric middle s_mid = (s_0 + s_1)/2 of the period's path piece: the drives' chord
//     departs from the law in actuator space, so only the geometry of L(s) matters, not how fast s advances
//     (with Smirnov's constant nominal speed the two middles coincide). Where it fails, the path piece is
//     shortened: the chord error grows with the square of its length, so Δτ·sqrt(ΔL_allowed/ΔL_max) meets it
//     (eq. 159, t̃* = sqrt(4·ΔL_allowed/|T2|)), checked again until it holds: the contour speed drops, real
//     time runs ahead of ideal time (eq. 160);
//  3. drive limits: no actuator moves more than its speed limit allows in h, nor more steps than its drive's
//     step rate (one step kept for rounding), at any override;
//  4. the last period ends exactly at the end of the path (§5.2.2).
#include <array>
#include <optional>

#include "core/result.hpp"
#include "interpolation/methods/feed_override.hpp"
#include "interpolation/methods/ideal_timing.hpp"
#include "interpolation/methods/strut_laws.hpp"

namespace pkm::interpolation {

struct CarrierSettings {
  double period_s = 0.001;
  bool chord_check = true;
  double strut_tolerance = 9e-5;  ///< ΔL_allowed (eq. 155), mm (rad for angular actuators)
  /// Largest increment per period (mm or rad) per actuator from speed limits and drive step rates; ∞: none.
  std::array<double, kMaxActuators> max_increment{};
  OverrideSettings feed_override;
  long max_periods = 100'000'000;  ///< a guard against a run that cannot end
};

struct CarrierPeriod {
  long index = 0;
  double time_s = 0.0;  ///< real time at the period's end, (index + 1)·h
  double tau_start_s = 0.0, tau_end_s = 0.0;
  double s_start = 0.0, s_end = 0.0;
  int hint = 0;                                ///< strut-law piece at the end
  std::array<double, kMaxActuators> start{};   ///< ideal actuator values at the start
  std::array<double, kMaxActuators> target{};  ///< ideal actuator values at the end
  double override_factor = 1.0;
  double chord_error = 0.0;  ///< largest |ΔL_max| of the period's chords
  bool reduced_by_chord = false;
  bool reduced_by_drives = false;
  bool last = false;
};

struct CarrierStatistics {
  long periods = 0;
  long chord_reduced_periods = 0;
  long drive_reduced_periods = 0;
  double max_chord_error = 0.0;
  double ideal_time_s = 0.0;  ///< τ_Tr
  double real_time_s = 0.0;   ///< periods·h
};

class CarrierInterpolator {
 public:
  /// `laws` and `timing` must outlive the interpolator. Errors: the start of the path out of reach.
  CarrierInterpolator(const StrutLaws& laws, const IdealTiming& timing, const CarrierSettings& settings);
  Status start(std::array<double, kMaxActuators>& start_values);
  /// The next period; false after the last one or on error (error()). No allocation.
  bool next(CarrierPeriod& period);
  const std::optional<Error>& error() const { return error_; }
  const CarrierStatistics& statistics() const { return statistics_; }

 private:
  bool evaluate(double s, std::array<double, kMaxActuators>& values);

  const StrutLaws& laws_;
  const IdealTiming& timing_;
  CarrierSettings settings_;
  FeedOverride override_;
  int count_ = 0;
  long index_ = 0;
  double tau_ = 0.0;
  double s_ = 0.0;
  int hint_ = 0;
  bool done_ = false;
  std::array<double, kMaxActuators> values_{};
  std::optional<Error> error_;
  CarrierStatistics statistics_;
};

}  // namespace pkm::interpolation
