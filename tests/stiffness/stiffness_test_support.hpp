#pragma once
// What the stiffness tests share: random strut stiffness for the generated machines.
#include <random>

#include "machine/stiffness_parameters.hpp"

namespace pkm::test {

/// Every strut's axial stiffness drawn uniformly from [lowest, highest] N/mm (the strut-only model).
inline StiffnessParameters random_strut_stiffness(std::mt19937_64& rng, int struts, double lowest_N_mm,
                                                  double highest_N_mm) {
  std::uniform_real_distribution<double> stiffness(lowest_N_mm, highest_N_mm);
  StiffnessParameters p;
  p.strut_count = struts;
  p.line = 1;
  for (int j = 0; j < struts; ++j) p.struts[j].stiffness_N_mm = stiffness(rng);
  return p;
}

}  // namespace pkm::test
