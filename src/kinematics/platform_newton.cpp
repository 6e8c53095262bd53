#include "kinematics/platform_newton.hpp"

#include <string>

namespace pkm::detail {

Error platform_fk_error(const PlatformFkFailure& failure, const FkOptions& options) {
  switch (failure.kind) {
    case PlatformFkFailure::Kind::start_unreachable:
      return make_error(ErrorCode::unreachable,
                        "forward kinematics: the start guess is outside the reachable space");
    case PlatformFkFailure::Kind::singular_solution:
      return make_error(
          ErrorCode::singular,
          "forward kinematics: these actuator values put the mechanism in a singular configuration");
    case PlatformFkFailure::Kind::singular_path:
      return make_error(ErrorCode::singular,
                        "forward kinematics: the Jacobian is singular on the way to a solution "
                        "(the actuator values may lie at a singular configuration)");
    case PlatformFkFailure::Kind::not_converged:
      break;
  }
  return make_error(ErrorCode::not_converged,
                    "forward kinematics did not converge within " + std::to_string(options.max_iterations) +
                        " iterations (residual " + std::to_string(failure.residual_mm) +
                        " mm); give a guess closer to the solution");
}

}  // namespace pkm::detail
