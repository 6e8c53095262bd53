#pragma once
// The rigid-body terms of the equations of motion in a twist basis, M c̈ + bias = applied + J_Bᵀ P, in matrix
// form for hot paths (the elastic model's right-hand side runs ~15 000 times per simulated second).
//
// The bodies are those of body_motion.hpp. Every body's velocity is linear in the velocity of its strut's
// platform joint, ḃ_j = G_j t with G_j = [I, −[b_j − p]×]: with d = B − A = L u, P = I − u uᵀ and, for a
// carriage on its guide (∂A/∂q = e), W = e dᵀ / (d·e) (from |B − A(q)| = const; W = 0 for a fixed joint),
//   carriage  W ḃ,   lower part  (W + c_l U) ḃ,   upper part  (I − c_u U) ḃ,   strut  ω = [u]× U ḃ,
// U = P (I − W) / L (the rate of u). So M = Σ_j G_jᵀ S_j G_j + platform, with the 3 × 3
// S_j = Σ_bodies m Aᵀ A (+ I_t for the turn), and the bias and the applied forces are the bodies' rates of
// momentum at zero coordinate acceleration, and their weights, carried back by the same maps' transposes.
// Each is a sum of the powers coordinate_forces (equations_of_motion.hpp) takes body by body, so the two
// agree to rounding (tests/dynamics/elastic_model_test.cpp); this form needs no body evaluation per
// coordinate.
#include "dynamics/equations_of_motion.hpp"
#include "dynamics/mass_lower_triangle.hpp"

namespace pkm::dynamics {

struct RigidTerms {
  CoordinateMatrix mass;   ///< kg (mm coordinates), kg·mm² (rad coordinates)
  ActuatorVector bias;     ///< velocity-product terms, kg·mm/s²
  ActuatorVector applied;  ///< gravity and the load, kg·mm/s²
};

/// The same terms in the platform's own twist (tool-point velocity, angular velocity; no basis), with M as
/// its lower triangle (mass.lower after fold_sums()): what a right-hand side whose basis is the identity
/// needs, without the projection and the mirrored full matrix.
struct TwistRigidTerms {
  MassLowerTriangle mass;  ///< kg, kg·mm (the coupling), kg·mm²
  Twist bias;              ///< kg·mm/s², kg·mm²/s²
  Twist applied;
};

/// twist_rigid_terms: as rigid_terms() below, in the platform's own twist. Never allocates.
void twist_rigid_terms(const MechanismState& state, const DynamicsParameters& parameters, const Twist& twist,
                       const statics::Wrench& load, TwistRigidTerms& out);

/// M, bias (for the platform moving with `twist`) and applied (gravity, and `load` in N and N·mm about the
/// tool point) in the coordinates of `basis`, at a state with its pose, struts' ends, their unit directions
/// and lengths, base-joint motion and platform body filled (mechanism_state fills more). Never allocates.
void rigid_terms(const MechanismState& state, const DynamicsParameters& parameters, const TwistBasis& basis,
                 const Twist& twist, const statics::Wrench& load, RigidTerms& out);

}  // namespace pkm::dynamics
