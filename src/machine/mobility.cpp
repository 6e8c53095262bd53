#include "machine/mobility.hpp"

namespace pkm {

int spatial_mobility(int links, const std::array<int, 5>& p) {
  return 6 * (links - 1) - 5 * p[0] - 4 * p[1] - 3 * p[2] - 2 * p[3] - p[4];
}

int planar_mobility(int links, int one_dof_pairs, int two_dof_pairs) {
  return 3 * (links - 1) - 2 * one_dof_pairs - two_dof_pairs;
}

int mobility(const MechanismStructure& s) {
  return s.planar ? planar_mobility(s.links, s.pairs[0], s.pairs[1]) : spatial_mobility(s.links, s.pairs);
}

MechanismStructure structure_of(const Mechanism& mechanism) {
  return mechanism.structure();
}

}  // namespace pkm
