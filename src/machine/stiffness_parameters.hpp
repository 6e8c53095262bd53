#pragma once
// What the machine file's `stiffness:` section says about the elastic parts that carry a cutting load
// (docs/machine-file.md, docs/stiffness.md; spec glide_stiffness.md, ch3 V7). So far the struts: an axial
// stiffness c_j, or a modulus and a section whose stiffness E·A/L follows the strut's length.
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct StrutStiffness {
  double stiffness_N_mm = 0.0;  ///< c_j, when given as such
  double modulus_N_mm2 = 0.0;   ///< E, with area_mm2: c = E·A/L at the strut's length L
  double area_mm2 = 0.0;
  /// c at the strut length `length_mm` (mm between its joints), N/mm.
  double at_length(double length_mm) const {
    return area_mm2 > 0.0 ? modulus_N_mm2 * area_mm2 / length_mm : stiffness_N_mm;
  }
};

struct StiffnessParameters {
  int strut_count = 0;
  std::array<StrutStiffness, kMaxActuators> struts{};
  int line = 0;  ///< line of `stiffness:` in the machine file (0: not given)
  bool given() const { return line > 0; }
};

}  // namespace pkm
