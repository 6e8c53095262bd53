#pragma once
// From the twist Jacobian (actuator rates from tool-point velocity v and base-frame angular velocity ω) to
// the Jacobian in the user's pose coordinates (x, y, z, and angle rates of the named convention).
#include "core/rotation.hpp"
#include "kinematics/actuator_vector.hpp"
#include "kinematics/axis_mask.hpp"

namespace pkm {

/// twist_jacobian: n × 6 with columns (v, ω). Returns n × count(mask) with columns of the controlled
/// coordinates.
JacobianMatrix coordinate_jacobian(const JacobianMatrix& twist_jacobian, AngleConvention convention,
                                   const Eigen::Vector3d& angles_rad, const AxisMask& mask);

}  // namespace pkm
