#include "machine/machine.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"

namespace pkm {

void JointLimits::update_cosines() {
  base_joint_min_cos = base_joint_max_rad ? std::cos(*base_joint_max_rad) : -2.0;
  platform_joint_min_cos = platform_joint_max_rad ? std::cos(*platform_joint_max_rad) : -2.0;
}

Status check_actuator_range(const Machine& machine, const ActuatorVector& actuators) {
  const bool angular = machine.mechanism->actuators_are_angles();
  const char* unit = angular ? "deg" : "mm";
  auto shown = [angular](double v) { return angular ? deg_from_rad(v) : v; };
  for (int j = 0; j < actuators.size(); ++j) {
    if (machine.limits.min && actuators[j] < *machine.limits.min) {
      return make_error(ErrorCode::limit_exceeded,
                        fmt::format("actuator {} at {:.6f} {} is below actuator_min {} {} ({}:{})", j + 1,
                                    shown(actuators[j]), unit, shown(*machine.limits.min), unit,
                                    machine.source, machine.limits.min_line));
    }
    if (machine.limits.max && actuators[j] > *machine.limits.max) {
      return make_error(ErrorCode::limit_exceeded,
                        fmt::format("actuator {} at {:.6f} {} is above actuator_max {} {} ({}:{})", j + 1,
                                    shown(actuators[j]), unit, shown(*machine.limits.max), unit,
                                    machine.source, machine.limits.max_line));
    }
  }
  return ok_status();
}

}  // namespace pkm
