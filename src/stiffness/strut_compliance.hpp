#pragma once
// The tool's compliance when the struts are the only elastic parts (the strut-only model): each strut
// a spring of axial stiffness c_j along its line, the drives and every other part rigid. A small platform
// displacement δ = (d, θ) about the tool point stretches strut j by g_jᵀ δ, g_j = (u_j, a_j × u_j) its
// Plücker line about the tool point (u_j the unit direction A_j → B_j, a_j = B_j − p), so the stiffness in
// the twists the mechanism allows (all of them for six controlled coordinates, else the span of
// T = Mechanism::controlled_twists, so reduced-DOF machines keep their passive constraints rigid) is
//   K_T = Tᵀ Gᵀ diag(c) G T,          C = T K_T⁻¹ Tᵀ,          δ = C w
// for a wrench w = (f N, m N·mm about the tool point, base frame) on the platform. For hexapods, tripods and
// planar machines the lines are the actuators' own (G = the twist Jacobian); glide machines' and rotopods'
// constant-length struts are springs between their joints.
// With the joints (StiffnessModel::struts_joints) each strut's spring is in series with the compliances along
// its line at its ends: the joints' translational K_u, and for a strut on a carriage its drive and its guide,
//   1/c_j,eff = 1/c_j + K_u,base + K_u,platform + (n·a)²/k_d + C_g (1 − (n·â)²),
// n the strut's unit line, a = ∂A_j/∂q_j how the carriage moves with its drive (Mechanism::base_joint_motion:
// the guide direction e for a straight guide, so the drive term is (n·e)²/k_d; for a drive of
// angle the lever arm too) and the guide giving way across â only (its nᵀ C_g n with C_g = C_g (I − â âᵀ)).
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
  ActuatorVector strut_stiffness_N_mm;  ///< c_j,eff at this pose (E·A/L follows the length; in series)
  ActuatorVector strut_length_mm;
  /// Row j: strut j's Plücker line g_j = (u_j, (B_j − p) × u_j) about the tool point, so that a
  /// displacement δ stretches it by g_jᵀ δ and pulls it with the tension c_j,eff g_jᵀ δ (N).
  Eigen::Matrix<double, Eigen::Dynamic, 6, 0, kMaxActuators, 6> strut_lines;
  /// True where c_j,eff g_jᵀ δ is the strut's tension (the struts' other ends held: not with an elastic
  /// frame).
  bool tensions_from_stretch = true;
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

/// The compliance (mm/N) in series with strut j's own spring along its unit line `u` under `stiffness.model`
/// (0 for StiffnessModel::struts): its joints, and its carriage whose motion per unit drive value is
/// `carriage_motion` (zero for a base-fixed joint).
double series_compliance_mm_N(const StiffnessParameters& stiffness, int strut, const Eigen::Vector3d& u,
                              const Eigen::Vector3d& carriage_motion);

/// Principal stiffness of the translational (or rotational) 3 × 3 block of C: the eigenvalues of the block
/// inverted, ascending, N/mm (N·mm/rad), with unit directions as columns. Directions the mechanism does not
/// allow (zero compliance) come out as infinite stiffness.
struct PrincipalStiffness {
  Eigen::Vector3d stiffness;
  Eigen::Matrix3d directions;
};
PrincipalStiffness principal_stiffness(const ToolCompliance& compliance, bool rotational);

}  // namespace pkm::stiffness
