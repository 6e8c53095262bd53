#pragma once
// Fixed-capacity actuator-space values: up to six actuator coordinates and the Jacobians that map pose rates
// onto them. Never allocate (the servo loop's types).
#include <Eigen/Core>

namespace pkm {

constexpr int kMaxActuators = 6;
/// Up to six actuator coordinates; fixed capacity, never allocates.
using ActuatorVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxActuators, 1>;
/// Actuator rates from controlled-coordinate rates: rows = actuators, columns = controlled coordinates.
using JacobianMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxActuators, 6>;
/// Platform twists per unit rate of each controlled coordinate: 6 × (controlled coordinates), rows
/// (v mm, ω rad) per mm or rad of the coordinate (Mechanism::controlled_twists).
using TwistBasis = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

}  // namespace pkm
