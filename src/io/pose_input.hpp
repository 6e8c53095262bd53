#pragma once
// User-facing pose numbers (mm and degrees) ↔ Pose, per mechanism:
//   planar2: x,y     planar3: x,y,phi     spatial: x,y,z,a1,a2,a3 in the machine's angle convention
//   (reduced-DOF spatial mechanisms also accept just their controlled coordinates, in order).
#include <string>
#include <string_view>
#include <vector>

#include "machine/mechanism.hpp"

namespace pkm {

/// Splits "1, 2.5,-3" into numbers; the error names `field`.
Result<std::vector<double>> parse_number_list(std::string_view text, std::string_view field);

/// Builds a (completed) pose from user numbers.
Result<Pose> pose_from_user(const Mechanism& mechanism, const std::vector<double>& values,
                            std::string_view field);
/// The user numbers of a pose (mm, degrees), as many as pose_from_user takes in full.
std::vector<double> user_from_pose(const Mechanism& mechanism, const Pose& pose);
/// Actuator numbers as users see them (mm, or degrees for angular actuators) ↔ internal.
Result<ActuatorVector> actuators_from_user(const Mechanism& mechanism, const std::vector<double>& values,
                                           std::string_view field);
std::vector<double> user_from_actuators(const Mechanism& mechanism, const ActuatorVector& actuators);
/// "mm" or "deg".
const char* actuator_unit_name(const Mechanism& mechanism);

}  // namespace pkm
