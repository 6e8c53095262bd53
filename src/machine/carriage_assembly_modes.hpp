#pragma once
// All assembly modes of the machines whose struts of constant length run from carriages to the platform (the
// hexaglide on straight guides, the rotopod on its circle). With the actuators given, every carriage joint
// C_j is a fixed point, and the platform's poses are those of a general Gough–Stewart platform with base
// joints C_j and strut lengths l_j: |p + R b_j − C_j| = l_j. So the hexapod's enumeration (the parameter
// homotopy from the generic 6-6 instance, 40 paths, hexapod_assembly_modes.cpp) finds every isolated one.
// Each solution is a pose of the machine; it is labelled 0 where it is the machine's own mode (its inverse
// kinematics, with the strut branches of the machine file, gives these actuators back, and its assembly-mode
// sign is home's; of several such mirror poses the nearest to home), else 1, 2, … nearest to home first.
//
// The triglide (three carriages, a platform held parallel) is three spheres: trilateration's two points.
#include <array>
#include <functional>

#include "kinematics/fk_solution.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

/// The modes of `mechanism` at `actuators`, its carriage joints `carriages_mm` (base frame) and platform
/// joints `platform_mm` (tool frame) with strut lengths `lengths_mm`; `same_mode(pose)`: the machine's own
/// assembly mode sign equals home's.
Result<AssemblyModes> carriage_assembly_modes(const Mechanism& mechanism, const ActuatorVector& actuators,
                                              const std::array<Eigen::Vector3d, 6>& carriages_mm,
                                              const std::array<Eigen::Vector3d, 6>& platform_mm,
                                              const std::array<double, 6>& lengths_mm,
                                              const FkOptions& options,
                                              const std::function<bool(const Pose&)>& same_mode);

/// The triglide's: the tool point B with |B + b_j − C_j| = l_j for its three carriages (the rotation held
/// at `rotation`), both mirror points where they are real.
Result<AssemblyModes> three_carriage_assembly_modes(const Mechanism& mechanism,
                                                    const ActuatorVector& actuators,
                                                    const std::array<Eigen::Vector3d, 3>& carriages_mm,
                                                    const std::array<Eigen::Vector3d, 3>& platform_mm,
                                                    const std::array<double, 3>& lengths_mm,
                                                    const Eigen::Matrix3d& rotation);

}  // namespace pkm
