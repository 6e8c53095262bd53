#include "pose_reach.hpp"

#include "machine/machine.hpp"

namespace pkm::cli {

Status pose_within_actuator_range(const Machine& machine, const Pose& pose) {
  auto q = machine.mechanism->inverse(pose);
  if (!q) return q.error();
  if (auto range = check_actuator_range(machine, *q); !range) {
    return make_error(ErrorCode::unreachable,
                      "pose unreachable within the actuator range: " + range.error().message);
  }
  return ok_status();
}

}  // namespace pkm::cli
