#pragma once
// Operator feed override during execution (Smirnov 2019, §5.2.2). The override K_V = V_set / V_nom (eq. 161)
// scales the advance of ideal time per real period: Δτ = K_V·h, which is exact for strut laws parametrised
// by the nominal motion (a consistent reading of eq. 162–164; the per-strut root finding of eq. 164 only
// approximates it and fails near velocity reversals).
//
// Timing: a change made during period i cannot affect period i+1, whose strut speeds were computed during
// period i; it takes effect from period i+2 (Fig. 170). The transition follows an acceleration-limited law
// from the time origin t_0 = t_H^<i+1> (eq. 165): period i+1 keeps the old value, period i+k uses the law at
// t_0 + (k−1)·h. The law is linear (constant acceleration, eq. 167, as in Smirnov's three controllers) or an
// S-curve (smoothstep: zero acceleration at both ends, bounded jerk).
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm::interpolation {

enum class RampShape { linear, s_curve };

struct OverrideChange {
  double time_s = 0.0;  ///< real time at which the operator sets it
  double percent = 100.0;
};

struct OverrideSettings {
  double initial_percent = 100.0;
  std::vector<OverrideChange> changes;  ///< in time order
  /// Time a change of 100 percentage points takes: the path acceleration limit brings the fastest feed
  /// from rest to full speed in this time (max feed / path acceleration).
  double full_ramp_s = 0.1;
  RampShape shape = RampShape::linear;
};

/// Parses "T:PCT,T:PCT,…" (seconds, percent 0…200) for --override-at; errors name the item.
Result<std::vector<OverrideChange>> parse_override_changes(const std::string& text);

/// K_V per period, with the i+2 rule and the ramp. Call factor(i) for i = 0, 1, 2, … in order.
class FeedOverride {
 public:
  FeedOverride(const OverrideSettings& settings, double period_s);
  /// The override factor (percent / 100) in effect during period `index`. No allocation.
  double factor(long index) noexcept;
  /// True when no later change can raise a zero override again (the run would never end).
  bool stalled() const noexcept;

 private:
  OverrideSettings settings_;
  double period_s_;
  std::size_t next_change_ = 0;
  double from_ = 1.0;  ///< factor before the current transition
  double to_ = 1.0;    ///< target of the current transition
  long origin_ = -1;   ///< period i+1 of the current transition (holds `from_`)
  double current_ = 1.0;
};

}  // namespace pkm::interpolation
