#include "planning/machine_warnings.hpp"

#include <fmt/format.h>

namespace pkm::planning {

namespace {

// A home tool point farther than this from the base frame's origin makes program zero at that origin a
// place no program means (a hexapod's base plane is hundreds of millimetres below its workspace).
constexpr double kOriginWarningDistanceMm = 50.0;

}  // namespace

std::vector<std::string> machine_warnings(const Machine& machine) {
  std::vector<std::string> warnings;
  const std::string& file = machine.source;
  // Carriages on a circle (the rotopod) turn for ever: a range is no part of such a machine.
  if ((!machine.limits.min || !machine.limits.max) && !machine.mechanism->actuators_are_angles()) {
    warnings.push_back(
        fmt::format("{}: no limits.actuator_min/actuator_max: every pose the inverse kinematics solves "
                    "counts as reachable",
                    file));
  }
  if (!machine.limits.speed || !machine.limits.accel) {
    warnings.push_back(fmt::format(
        "{}: no limits.actuator_speed/actuator_accel: only the path's feed, acceleration and jerk limit the "
        "actuators",
        file));
  }
  const double home_distance_mm = machine.mechanism->home().position_mm.norm();
  if (machine.motion.program_origin_mm.isZero() && home_distance_mm > kOriginWarningDistanceMm) {
    warnings.push_back(
        fmt::format("{}: no motion.program_origin_mm: program X0 Y0 Z0 is the base frame's origin, {:.1f} mm "
                    "from the home "
                    "tool point",
                    file, home_distance_mm));
  }
  return warnings;
}

}  // namespace pkm::planning
