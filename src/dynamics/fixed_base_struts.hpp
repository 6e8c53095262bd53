#pragma once
// The rigid terms (rigid_terms.hpp) of the struts whose base joints are fixed to the base, all struts at
// once: every quantity is a row of the struts' values, so that each operation runs over the struts in the
// processor's vector lanes instead of strut by strut in scalar 3-vector algebra (which spent about 470
// instructions per strut; the elastic right-hand side runs ~17 000 times per simulated second).
#include "dynamics/equations_of_motion.hpp"
#include "dynamics/mass_lower_triangle.hpp"

namespace pkm::dynamics {

/// Adds the struts with state.base_moves[j] false: their mass-matrix terms to `mass`, their rates of momentum
/// at zero twist rate (platform moving with `twist`) to `bias`, their weights to `applied` (kg·mm/s² and
/// kg·mm²/s² about the tool point). Reads the state's rows (set_strut_directions: the joints' arms, unit
/// directions and 1/L; fixed_base_constants, zero for struts on moving base joints). Never allocates.
void add_fixed_base_struts(const MechanismState& state, const DynamicsParameters& parameters,
                           const Twist& twist, MassLowerTriangle& mass, Twist& bias, Twist& applied);

}  // namespace pkm::dynamics
