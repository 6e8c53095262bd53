#include "stiffness/nc_compensation.hpp"

#include <fmt/format.h>

#include "core/rotation.hpp"

namespace pkm::stiffness {

Pose displaced(const Pose& pose, const Vector6& twist) {
  return Pose{pose.position_mm + twist.head<3>(),
              rotation_from_rotation_vector(twist.tail<3>()) * pose.rotation};
}

Result<CompensatedPose> compensate_pose(const Pose& nominal, const DeflectionAt& deflection,
                                        const CompensationOptions& options, const Pose* start) {
  CompensatedPose out;
  out.command = start ? *start : nominal;
  for (;;) {
    auto delta = deflection(out.command);
    if (!delta) return delta.error();
    const Pose reached = displaced(out.command, *delta);
    const PoseDistance residual = pose_distance(reached, nominal);
    out.residual_mm = residual.position_mm;
    out.residual_rad = residual.rotation_rad;
    if (out.residual_mm <= options.tolerance_mm && out.residual_rad <= options.tolerance_rad) return out;
    if (out.iterations == options.max_iterations) {
      return make_error(ErrorCode::not_converged,
                        fmt::format("the pre-compensation left {:.3g} mm and {:.3g} rad after {} iterations",
                                    out.residual_mm, out.residual_rad, out.iterations));
    }
    // x_cmd ← x_nom ⊖ δ(x_cmd).
    out.command = displaced(nominal, -*delta);
    ++out.iterations;
  }
}

}  // namespace pkm::stiffness
