#pragma once
// The links and kinematic pairs of a mechanism as Smirnov 2019 counts them (§1.2 table), for the
// Somov–Malyshev mobility formula (machine/mobility.hpp). Each mechanism states its own (Mechanism::
// structure), so that no stage needs a table over mechanism types.
#include <array>
#include <string>

namespace pkm {

struct MechanismStructure {
  std::string notation;  ///< e.g. "6-UPS", "3-RPR"
  bool planar = false;
  int links = 0;               ///< k, including the base
  std::array<int, 5> pairs{};  ///< pairs[i] = number of pairs with i + 1 DOF
  int idle_freedoms = 0;  ///< freedoms that move no output (a strut spinning between two spherical joints)
};

}  // namespace pkm
