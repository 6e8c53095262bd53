#pragma once
// Mobility (degrees of freedom) of a mechanism by the Somov–Malyshev formula (dissertation eq. 1, 2):
//   spatial  H = 6(k − 1) − 5p1 − 4p2 − 3p3 − 2p4 − p5
//   planar   H = 3(k − 1) − 2p1 − p2
// k counts every link including the base; p_i counts kinematic pairs with i degrees of freedom
// (prismatic/revolute/screw 1, cylindrical/universal 2, spherical 3).
#include <array>
#include <string>

#include "machine/mechanism.hpp"

namespace pkm {

int spatial_mobility(int links, const std::array<int, 5>& pairs_by_dof);
int planar_mobility(int links, int one_dof_pairs, int two_dof_pairs);
/// H of the structure (planar or spatial formula), idle freedoms not yet subtracted.
int mobility(const MechanismStructure& structure);

/// The structure of a loaded mechanism, as Smirnov 2019 counts it (§1.2 table): Mechanism::structure.
MechanismStructure structure_of(const Mechanism& mechanism);

}  // namespace pkm
