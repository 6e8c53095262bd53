#pragma once
// The 3-D Euler–Bernoulli beam of the frame model (Rusanov et al.: "Cantilever", "Beam", "Global
// frame"; docs/stiffness_frame.md). A beam's own axes are their cantilever frame: z along the beam, x
// and y the section's principal axes (machine/frame_parameters.hpp). Every displacement is a twist (u mm, φ
// rad) and every load a wrench (Q N, M N·mm), rotations and moments as right-handed vectors.
//
// The cantilever, clamped at s = 0 and loaded at its free end s = L, with the sign couplings derived once
// from the elastic line (corrected: entry (1,1) is L³/(3EJ_y), and the printed signs of the couplings do not
// make a symmetric matrix). The moment at a section is M(s) = M + (L − s) e_z × Q; the curvature κ =
// (M_x/EJ_x, M_y/EJ_y, M_z/GJ_t) turns the section, φ(s) = ∫₀ˢ κ; the centre line follows du/ds = φ × e_z +
// e_z Q_z/EF:
//   u_x =  Q_x L³/(3EJ_y) + M_y L²/(2EJ_y)     φ_y =  Q_x L²/(2EJ_y) + M_y L/(EJ_y)
//   u_y =  Q_y L³/(3EJ_x) − M_x L²/(2EJ_x)     φ_x = −Q_y L²/(2EJ_x) + M_x L/(EJ_x)
//   u_z =  Q_z L/(EF)                          φ_z =  M_z L/(GJ_t)
// A force along +x bends the tip towards +x and turns it about +y (e_y × e_z = e_x), one along +y turns it
// about −x: the couplings of the two planes have opposite signs, and each is the same in both places of C.
#include <Eigen/Core>

#include "machine/frame_parameters.hpp"

namespace pkm::stiffness {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

/// [u; φ] of the free end per [Q; M] on it, the other end clamped, in the beam's axes (the table above).
Matrix6 cantilever_compliance(const BeamSection& section, double length_mm);

/// The free end's stiffness: cantilever_compliance inverted in closed form (per bending plane
/// EJ [12/L³ ∓6/L²; ∓6/L² 4/L], axial EF/L, torsion GJ_t/L).
Matrix6 cantilever_stiffness(const BeamSection& section, double length_mm);

/// How a rigid body's motion (u, φ) at one point shows at a point `offset_mm` away: u + φ × r, φ; as the
/// matrix H = [I −[r]×; 0 I]. Its transpose moves a wrench back: (Q, M + r × Q).
Matrix6 rigid_transfer(const Eigen::Vector3d& offset_mm);

/// The 12 × 12 stiffness of a beam of `length_mm` in its own axes, nodes 0 (s = 0) and 1 (s = L), each with
/// (u_x, u_y, u_z, φ_x, φ_y, φ_z). From Rusanov's "Beam" relation: node 1 moves relative to node 0's rigid
/// motion, q₁ − H q₀ = C [Q₁; M₁] (H = rigid_transfer(L e_z)), and node 0 takes the reaction −Hᵀ [Q₁; M₁]:
///   K = [Hᵀ K₁₁ H   −Hᵀ K₁₁;   −K₁₁ H   K₁₁],   K₁₁ = C⁻¹ = cantilever_stiffness.
Matrix12 beam_stiffness_local(const BeamSection& section, double length_mm);

/// The beam's axes as the rows of γ (base-frame components): z along `axis` (unit), x the part of
/// `section_x` square to it, y = z × x; local components are γ times base-frame ones. `section_x` must not be
/// parallel to the axis (the frame reader refuses it).
Eigen::Matrix3d beam_axes(const Eigen::Vector3d& axis, const Eigen::Vector3d& section_x);

/// The beam from `from_mm` to `to_mm` in the base frame ("Global frame": Γᵀ K Γ, Γ = diag(γ, γ, γ, γ)).
Matrix12 beam_stiffness_global(const BeamSection& section, const Eigen::Vector3d& from_mm,
                               const Eigen::Vector3d& to_mm, const Eigen::Vector3d& section_x);

}  // namespace pkm::stiffness
