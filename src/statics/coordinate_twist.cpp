#include "statics/coordinate_twist.hpp"

namespace pkm::statics {

Result<TwistBasis> controlled_twist_basis(const Mechanism& mechanism, const Pose& completed_pose) {
  TwistBasis basis;
  if (!mechanism.controlled_twists(completed_pose, basis)) {
    return make_error(
        ErrorCode::singular,
        "statics: the platform's motion per controlled coordinate is not determined here (the pose "
        "is out of reach or the mechanism's constraints are singular)");
  }
  return basis;
}

}  // namespace pkm::statics
