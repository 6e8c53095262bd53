#pragma once
// How the platform moves when one controlled coordinate changes: the matrix T_c whose column i is the twist
// (tool-point velocity v, base-frame angular velocity ω) per unit rate of controlled coordinate i. It turns a
// wrench into generalised forces, Q = T_cᵀ w, so that the virtual work of the load is Q · dq (the principle
// behind the seed's statics (73)/(91): only motions the mechanism allows do work).
#include <Eigen/Core>

#include "machine/mechanism.hpp"

namespace pkm::statics {

/// 6 × m, m = controlled coordinates (≤ 6); rows (v mm, ω rad) per (mm or rad) of coordinate.
using TwistBasis = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

/// Finite-difference steps for mechanisms whose dependent coordinates move (tripod, tricept): central
/// differences of Mechanism::complete_pose, error O(h²) ≈ 1e-12 relative at machine sizes, rounding ≈ 1e-10.
constexpr double kTwistStepMm = 1e-3;
constexpr double kTwistStepRad = 1e-5;

/// T_c at a completed pose, columns in the order of Mechanism::jacobian (the controlled coordinates).
///  - all six coordinates controlled: analytic [I 0; 0 E(angles)] (E: rotation.hpp, ω = E · angle rates);
///  - planar mechanisms: the same columns for x, y and φ (rotation about z); the others are fixed;
///  - other reduced-DOF mechanisms: central differences of complete_pose, since x, y, or the angles follow
///    the controlled coordinates through the mechanism's constraints.
/// Fails when a perturbed pose cannot be completed (the pose is at the edge of the workspace).
Result<TwistBasis> controlled_twist_basis(const Mechanism& mechanism, const Pose& completed_pose);

}  // namespace pkm::statics
