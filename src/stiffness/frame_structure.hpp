#pragma once
// The frame of beams on its own (docs/stiffness_frame.md): which nodes move (six DOF each, (u mm, φ rad) in
// the base frame; fixed nodes are removed), the beams' stiffness in the base frame, whether the supports hold
// every node, and the frame's displacements under nodal loads (the check that splitting beams changes
// nothing, and a reference for the full model).
#include <Eigen/Core>
#include <vector>

#include "core/result.hpp"
#include "machine/frame_parameters.hpp"
#include "stiffness/beam_element.hpp"

namespace pkm::stiffness {

using Vector6 = Eigen::Matrix<double, 6, 1>;

/// The first of each node's six DOF in the frame's numbering, −1 for fixed nodes; `count` DOF in all.
struct FrameDofs {
  std::vector<int> first;
  int count = 0;
};
FrameDofs number_frame_dofs(const FrameParameters& frame);

/// Each beam's 12 × 12 stiffness in the base frame (beam_stiffness_global), in the order of frame.beams.
std::vector<Matrix12> frame_beam_stiffness(const FrameParameters& frame);

/// Fails (ErrorCode::singular, "FILE:LINE: stiffness.frame: singular stiffness matrix: the frame is a
/// mechanism …" naming the first such node) when a free node is not joined through beams to a fixed node:
/// that part of the frame moves as a rigid body (a mechanism), and its stiffness matrix is singular.
Status check_frame_supported(const FrameParameters& frame);

/// The frame's nodal displacements (u mm, φ rad; zero at fixed nodes) under nodal loads (Q N, M N·mm, base
/// frame; one per node, those at fixed nodes go into the supports). Fails as check_frame_supported.
Result<std::vector<Vector6>> frame_displacements(const FrameParameters& frame,
                                                 const std::vector<Vector6>& loads);

/// The error of a frame that is a mechanism, at the `stiffness.frame` key (ErrorCode::singular).
Error frame_mechanism_error(const FrameParameters& frame, const std::string& detail);

}  // namespace pkm::stiffness
