#include "execution/machine_headroom.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace pkm::execution {

Result<ExecutionHeadroom> machine_headroom(const Machine& machine, double period_s) {
  if (!machine.limits.speed || !machine.limits.accel) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: executing a program needs the drives' limits: limits.actuator_speed "
                                  "and limits.actuator_accel",
                                  machine.source));
  }
  auto headroom = execution_headroom({*machine.limits.speed, *machine.limits.accel, std::nullopt},
                                     kExecutionMaxOverride, kExecutionMotionShare, period_s);
  if (!headroom) {
    return make_error(
        headroom.error().code,
        fmt::format("{}:{}: {}", machine.source, machine.limits.accel_line, headroom.error().message));
  }
  return headroom;
}

double step_in_actuator_units(const Machine& machine, double step) {
  return machine.mechanism->actuators_are_angles() ? rad_from_deg(step) : step;
}

Result<ExecutorSettings> executor_settings(const Machine& machine, double step, double period_s) {
  auto headroom = machine_headroom(machine, period_s);
  if (!headroom) return headroom.error();
  ExecutorSettings settings;
  settings.drives = machine.mechanism->actuator_count();
  settings.period_s = period_s;
  settings.max_override = headroom->max_override;
  settings.rates = headroom->rates;  // K̇ and K̈ have no unit: the same in steps
  const double unit = step_in_actuator_units(machine, step);
  // No stop given: far beyond any position a drive reaches, with room to spare in 64 bits.
  constexpr std::int64_t kFar = std::int64_t{1} << 60;
  for (int j = 0; j < kMaxActuators; ++j) {
    settings.min_position_steps[j] =
        machine.limits.min ? static_cast<std::int64_t>(std::ceil(*machine.limits.min / unit - 1e-9)) : -kFar;
    settings.max_position_steps[j] =
        machine.limits.max ? static_cast<std::int64_t>(std::floor(*machine.limits.max / unit + 1e-9)) : kFar;
  }
  return settings;
}

}  // namespace pkm::execution
