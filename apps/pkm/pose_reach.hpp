#pragma once
// One answer to "can the machine be at this pose?" for the commands that take a --pose (ik, jacobian): a
// pose one of them refuses, the others refuse alike, with the same exit code.
#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm::cli {

/// The pose's inverse kinematics, within the actuator range: the inverse's own error (unreachable), or
/// ErrorCode::unreachable "pose unreachable within the actuator range: …" (exit 3).
Status pose_within_actuator_range(const Machine& machine, const Pose& pose);

}  // namespace pkm::cli
