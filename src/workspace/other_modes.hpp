#pragma once
// The other assembly modes of a pose's actuator values: how many real assembly modes the actuator
// values q0 = IK(X0) have, and how far the nearest other one is from X0, by Mechanism::forward_all. Where the
// mechanism cannot enumerate its modes (forward_all answers "unsupported": 6-6 hexapods, glides, the rotopod,
// the tricept), the counts and distances stay empty with the mechanism's reason; that is no failure.
//
// "Nearest" is by |Δp| + L·|Δθ| (mm), L = Mechanism::platform_size_mm(), as forward_all orders its solutions
// (machine/solution_set.hpp); its position and rotation parts are reported separately.
#include <limits>
#include <string>

#include "machine/mechanism.hpp"

namespace pkm::workspace {

struct OtherAssemblyModes {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  bool enumerated = false;                    ///< forward_all answered; otherwise the fields below stay empty
  int real_modes = -1;                        ///< real assembly modes of q0, X0's own included
  bool current_found = false;                 ///< one of them is X0 (within `same_mode_mm`)
  double nearest_other_position_mm = kNone;   ///< |Δp| to the nearest other mode
  double nearest_other_rotation_deg = kNone;  ///< the rotation between X0 and that mode
  double nearest_other_distance_mm = kNone;   ///< |Δp| + L·|Δθ| of that mode, what "nearest" compares
  Pose nearest_other;                         ///< that mode's pose
  std::string note;  ///< why there is no count (forward_all's message), or that X0 was not among the modes
};

/// The assembly modes of `actuators` (IK of `pose`) and the nearest one other than `pose`'s. A solution
/// within `same_mode_mm` of `pose` (by |Δp| + L·|Δθ|) is `pose`'s own mode.
OtherAssemblyModes other_assembly_modes(const Mechanism& mechanism, const Pose& pose,
                                        const ActuatorVector& actuators, double same_mode_mm = 1e-4);

}  // namespace pkm::workspace
