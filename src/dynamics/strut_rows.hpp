#pragma once
// The struts' quantities as rows of one value per strut (structure of arrays): the hot paths of the
// time-domain models (the elastic right-hand side runs ~17 000 times per simulated second) run each
// operation over all struts in the processor's vector lanes, two struts per SSE2 instruction, instead of
// strut by strut in scalar 3-vector algebra. Lanes past the mechanism's struts hold zeros.
#include <Eigen/Core>

#include "machine/dynamics_parameters.hpp"
#include "machine/mechanism.hpp"

namespace pkm::dynamics {

/// One value per strut.
using StrutRow = Eigen::Array<double, 1, kMaxActuators>;

/// A 3-vector per strut, by components.
struct StrutRows3 {
  StrutRow x = StrutRow::Zero(), y = StrutRow::Zero(), z = StrutRow::Zero();
};

/// The constants of the struts' rigid terms on fixed base joints (fixed_base_struts.hpp), which depend only
/// on the dynamics parameters: made once per model (free_platform.hpp) instead of at every evaluation.
struct FixedBaseStrutConstants {
  StrutRow upper_kg = StrutRow::Zero();            ///< m_u
  StrutRow upper_moment_kg_mm = StrutRow::Zero();  ///< m_u c_u
  StrutRow lower_moment_kg_mm = StrutRow::Zero();  ///< m_l c_l
  StrutRow turning_kg_mm2 = StrutRow::Zero();      ///< J = m_l c_l² + m_u c_u² + I_t, about the base joint
};

/// The constants of the first `struts` struts of `parameters` (zero in the other lanes).
inline FixedBaseStrutConstants fixed_base_strut_constants(const DynamicsParameters& parameters, int struts) {
  FixedBaseStrutConstants c;
  for (int j = 0; j < struts; ++j) {
    const StrutDynamics& p = parameters.struts[j];
    c.upper_kg[j] = p.upper.mass_kg;
    c.upper_moment_kg_mm[j] = p.upper.mass_kg * p.upper.com_mm;
    c.lower_moment_kg_mm[j] = p.lower.mass_kg * p.lower.com_mm;
    c.turning_kg_mm2[j] = c.lower_moment_kg_mm[j] * p.lower.com_mm +
                          c.upper_moment_kg_mm[j] * p.upper.com_mm + p.lower.transverse_inertia_kg_mm2 +
                          p.upper.transverse_inertia_kg_mm2;
  }
  return c;
}

}  // namespace pkm::dynamics
