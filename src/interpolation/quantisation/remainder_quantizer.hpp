#pragma once
// Whole drive steps per period with remainder registers (Smirnov 2019, eq. 156–158): each period an actuator
// is asked for its ideal increment d_j; the register R_j collects it, the whole steps in R_j are issued and
// taken out of it:
//   R_j += d_j;   n_j = trunc(R_j / Δ);   R_j −= n_j·Δ,
// truncating toward zero, so |R_j| < Δ through velocity reversals too (Smirnov leaves the negative direction
// open; struts 2 and 3 reverse on their standard test line). Each actuator's issued steps therefore stay
// within one step of its ideal net change; the last period empties the registers to the nearest step (the
// path's end, §5.2.2), so the net change ends within half a step. This is Smirnov's "naive" scheme: the start
// positions are the ideal ones truncated to whole steps, and that start error is kept along the path (§5.2.5,
// Figs. 189–190).
#include <array>

#include "interpolation/methods/carrier_interpolator.hpp"
#include "interpolation/quantisation/step_period.hpp"

namespace pkm::interpolation {

/// Start positions: the ideal values truncated to whole steps (the rounding of Smirnov 2019, §5.2.5).
std::array<std::int64_t, kMaxActuators> truncated_steps(const std::array<double, kMaxActuators>& values,
                                                        int count, double step);

class RemainderQuantizer {
 public:
  RemainderQuantizer(int actuators, double step);
  void start(const std::array<double, kMaxActuators>& ideal_start);
  /// Fills `out.steps` and `out.position` (and index, time, not the line). No allocation.
  void quantize(const CarrierPeriod& period, StepPeriod& out);
  const std::array<std::int64_t, kMaxActuators>& position() const { return position_; }
  /// Largest |R_j| left after a period, in steps (< 1 by construction).
  double max_remainder_steps() const { return max_remainder_steps_; }

 private:
  int count_;
  double step_;
  std::array<std::int64_t, kMaxActuators> position_{};
  std::array<double, kMaxActuators> remainder_{};
  double max_remainder_steps_ = 0.0;
};

}  // namespace pkm::interpolation
