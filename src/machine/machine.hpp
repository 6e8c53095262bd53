#pragma once
// A machine: its mechanism plus what the machine file says about limits and where it came from.
#include <memory>
#include <optional>
#include <string>

#include "machine/mechanism.hpp"

namespace pkm {

/// Actuator limits from the machine file. Lengths in mm (angular actuators: rad), speeds per s, accelerations
/// per s². `*_line` is the line of the key in the machine file, for messages (0 = not given).
struct ActuatorLimits {
  std::optional<double> min;
  std::optional<double> max;
  std::optional<double> speed;
  std::optional<double> accel;
  int min_line = 0;
  int max_line = 0;
};

struct Machine {
  std::string source;  ///< file the machine came from
  std::string name;
  std::unique_ptr<Mechanism> mechanism;
  ActuatorLimits limits;
  bool home_given = false;
};

/// Checks actuator positions against the machine's range; the error names the actuator, the value, the limit,
/// and the machine file line that set it.
Status check_actuator_range(const Machine& machine, const ActuatorVector& actuators);

}  // namespace pkm
