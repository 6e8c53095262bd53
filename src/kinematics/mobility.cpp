#include "kinematics/mobility.hpp"

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
  const int n = mechanism.actuator_count();
  switch (mechanism.type()) {
    case MechanismType::planar2:  // base, two two-part struts; 5 one-DOF pairs (B joins both struts)
      return {"2-RPR (planar, one output joint)", true, 5, {5, 0, 0, 0, 0}, 0};
    case MechanismType::planar3:  // base, platform, three two-part struts; 9 one-DOF pairs
      return {"3-RPR (planar)", true, 8, {9, 0, 0, 0, 0}, 0};
    case MechanismType::hexapod:
    case MechanismType::hexapod_refined:  // 6 × (U, P or H, S); base + platform + 12 strut parts
      return {"6-UPS", false, 14, {6, 6, 6, 0, 0}, 0};
    case MechanismType::tripod:  // 3 × (R, P, S)
      return {"3-RPS", false, 8, {6, 0, 3, 0, 0}, 0};
    case MechanismType::tricept:  // 3 × (U, P, S) + central leg (U, P) fixed to the flange
      return {"3-UPS + UP", false, 9, {4, 4, 3, 0, 0}, 0};
    case MechanismType::rotopod:  // 6 × (carriage R on the circle, U, S) with constant-length struts
      return {"6-RUS (rotopod)", false, 14, {6, 6, 6, 0, 0}, 0};
    case MechanismType::glide:
      if (n == 6) return {"6-PUS (hexaglide)", false, 14, {6, 6, 6, 0, 0}, 0};
      // Triglide: each carriage drives a parallelogram of two S–S struts; each strut can spin idly about its
      // axis.
      return {"3-P(2S-2S) (triglide)", false, 1 + 3 + 6 + 1, {3, 0, 12, 0, 0}, 6};
  }
  return {};
}

}  // namespace pkm
