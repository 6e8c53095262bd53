#pragma once
// The tool's compliance when the struts are the only elastic parts (issue 15's strut-only model): each strut
// a spring of axial stiffness c_j along its line, the drives and every other part rigid. A small platform
// displacement δ = (d, θ) about the tool point stretches strut j by g_jᵀ δ, g_j = (u_j, a_j × u_j) its
// Plücker line about the tool point (u_j the unit direction A_j → B_j, a_j = B_j − p), so the stiffness in
// the twists the mechanism allows (all of them for six controlled coordinates, else the span of
// T = Mechanism::controlled_twists, so reduced-DOF machines keep their passive constraints rigid) is
//   K_T = Tᵀ Gᵀ diag(c) G T,          C = T K_T⁻¹ Tᵀ,          δ = C w
// for a wrench w = (f N, m N·mm about the tool point, base frame) on the platform. For hexapods, tripods and
// planar machines the lines are the actuators' own (G = the twist Jacobian); glide machines' and rotopods'
// constant-length struts are springs between their joints all the same (their drives rigid, for now).
// Units: mm, rad, N; compliance blocks mm/N, mm/(N·mm) = 1/N, rad/N, rad/(N·mm).
#include <Eigen/Core>

#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm::stiffness {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct ToolCompliance {
  Pose pose;                            ///< the completed pose
  Matrix6 compliance;                   ///< δ per w, symmetric positive semi-definite (rank = dof)
  int dof = 0;                          ///< the platform motions the mechanism allows
  ActuatorVector strut_stiffness_N_mm;  ///< c_j at this pose (E·A/L follows the length)
  ActuatorVector strut_length_mm;
};

/// The struts' stiffness of `machine`: its `stiffness:` section, or else the elastic elements of its
/// `dynamics:` section (the same springs, docs/stiffness.md). Fails, naming the file and the key, when
/// neither gives every strut a stiffness.
Result<StiffnessParameters> strut_stiffness_of(const Machine& machine);

/// The compliance at `pose`. Fails where the pose is out of reach (unreachable), where the struts cannot
/// hold the platform in some allowed direction (singular: "unbounded compliance"), or where the mechanism's
/// struts do not match the parameters (unsupported).
Result<ToolCompliance> strut_compliance(const Mechanism& mechanism, const StiffnessParameters& stiffness,
                                        const Pose& pose);

/// Principal stiffness of the translational (or rotational) 3 × 3 block of C: the eigenvalues of the block
/// inverted, ascending, N/mm (N·mm/rad), with unit directions as columns. Directions the mechanism does not
/// allow (zero compliance) come out as infinite stiffness.
struct PrincipalStiffness {
  Eigen::Vector3d stiffness;
  Eigen::Matrix3d directions;
};
PrincipalStiffness principal_stiffness(const ToolCompliance& compliance, bool rotational);

}  // namespace pkm::stiffness
