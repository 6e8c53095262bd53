#include "interpolation/quantisation/remainder_quantizer.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::interpolation {

std::array<std::int64_t, kMaxActuators> truncated_steps(const std::array<double, kMaxActuators>& values,
                                                        int count, double step) {
  std::array<std::int64_t, kMaxActuators> steps{};
  // A small allowance keeps values that are whole steps up to round-off (603.122 mm = 603122 µm steps).
  for (int j = 0; j < count; ++j) steps[j] = static_cast<std::int64_t>(std::trunc(values[j] / step + 1e-9));
  return steps;
}

RemainderQuantizer::RemainderQuantizer(int actuators, double step) : count_(actuators), step_(step) {}

void RemainderQuantizer::start(const std::array<double, kMaxActuators>& ideal_start) {
  position_ = truncated_steps(ideal_start, count_, step_);
  remainder_.fill(0.0);
}

void RemainderQuantizer::quantize(const CarrierPeriod& period, StepPeriod& out) {
  out.index = period.index;
  out.time_s = period.time_s;
  for (int j = 0; j < count_; ++j) {
    remainder_[j] += period.target[j] - period.start[j];  // eq. 156: the ideal increment of this period
    // The last period ends the path (§5.2.2): the register is emptied to the nearest whole step.
    const double whole = period.last ? std::round(remainder_[j] / step_) : std::trunc(remainder_[j] / step_);
    remainder_[j] -= whole * step_;  // eq. 157/158
    const auto steps = static_cast<std::int32_t>(whole);
    out.steps[j] = steps;
    position_[j] += steps;
    out.position[j] = position_[j];
    max_remainder_steps_ = std::max(max_remainder_steps_, std::abs(remainder_[j]) / step_);
  }
}

}  // namespace pkm::interpolation
