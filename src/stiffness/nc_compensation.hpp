#pragma once
// NC pre-compensation (Rusanov et al.'s "correction of the NC program" from the predicted deflections):
// the commanded pose x_cmd whose deflected pose under the cutting load is the nominal one,
//   x_cmd ⊕ δ(x_cmd) = x_nom,
// ⊕ applying a small twist δ = (d mm, θ rad) about the tool point: position + d, rotation exp(θ̂)·R. The fixed
// point x_cmd ← x_nom ⊖ δ(x_cmd), started at x_nom, is exact after one step where δ does not depend on the
// pose and otherwise contracts by about |δ|/L per step (L the struts' length: 10⁻⁵ for µm deflections of
// metre struts). For the strut-only model of a machine whose actuators are its struts' lengths the
// closed form L_cmd = IK(x_nom) − T/c (the tension T at the nominal pose stretches each strut by T/c, so it
// is commanded that much shorter) gives the start, x_cmd = FK(L_cmd); the fixed point then removes the
// remaining second-order part. The residual |x_cmd ⊕ δ(x_cmd) − x_nom| is reported either way.
#include <functional>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "stiffness/tool_deflection.hpp"

namespace pkm::stiffness {

struct CompensationOptions {
  int max_iterations = 5;
  double tolerance_mm = 1e-7;    ///< of the residual's position
  double tolerance_rad = 1e-10;  ///< of the residual's rotation
};

struct CompensatedPose {
  Pose command;              ///< the pose to program
  double residual_mm = 0.0;  ///< |position of x_cmd ⊕ δ(x_cmd) − nominal|
  double residual_rad = 0.0;
  int iterations = 0;  ///< deflections evaluated after the start
};

/// The pose displaced by the small twist (d, θ): position + d, rotation exp(θ̂)·R.
Pose displaced(const Pose& pose, const Vector6& twist);

/// The deflection δ(x) of the tool at a commanded pose x (under the load of the nominal point).
using DeflectionAt = std::function<Result<Vector6>(const Pose& command)>;

/// x_cmd by the fixed point from `start` (x_nom when not given). Fails as `deflection` does, and with
/// not_converged when the residual is still above the tolerance after max_iterations.
Result<CompensatedPose> compensate_pose(const Pose& nominal, const DeflectionAt& deflection,
                                        const CompensationOptions& options = {}, const Pose* start = nullptr);

}  // namespace pkm::stiffness
