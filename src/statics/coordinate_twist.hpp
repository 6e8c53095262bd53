#pragma once
// How the platform moves when one controlled coordinate changes: the matrix T_c whose column i is the twist
// (tool-point velocity v, base-frame angular velocity ω) per unit rate of controlled coordinate i. It turns a
// wrench into generalised forces, Q = T_cᵀ w, so that the virtual work of the load is Q · dq (the principle
// behind Smirnov 2019's statics (73)/(91): only motions the mechanism allows do work).
#include <Eigen/Core>

#include "machine/mechanism.hpp"

namespace pkm::statics {

using pkm::TwistBasis;

/// T_c at a completed pose, columns in the order of Mechanism::jacobian (the controlled coordinates), from
/// Mechanism::controlled_twists (analytic for every mechanism: the tripod and tricept differentiate their
/// constraints). Fails, with a message, where the mechanism cannot give it.
Result<TwistBasis> controlled_twist_basis(const Mechanism& mechanism, const Pose& completed_pose);

}  // namespace pkm::statics
