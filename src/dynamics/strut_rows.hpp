#pragma once
// The struts' quantities as rows of one value per strut (structure of arrays): the hot paths of the
// time-domain models (the elastic right-hand side runs ~17 000 times per simulated second) run each
// operation over all struts in the processor's vector lanes, two struts per SSE2 instruction, instead of
// strut by strut in scalar 3-vector algebra. Lanes past the mechanism's struts hold zeros.
#include <Eigen/Core>
#include <cmath>

#include "machine/dynamics_parameters.hpp"
#include "machine/mechanism.hpp"

namespace pkm::dynamics {

/// One value per strut, in kMaxActuators / 2 pairs of doubles. Its arithmetic is written on GCC/Clang vector
/// extensions and always inlined: as an Eigen array of six, the right-hand side's long expressions left
/// Eigen's assignment kernels out of line (a call and the operands through memory per operation, about a
/// fifth of the fixed-base terms' instructions, callgrind).
class StrutRow {
 public:
  using Lane = double __attribute__((vector_size(16)));
  static constexpr int kLanes = (kMaxActuators + 1) / 2;

  StrutRow() = default;
  [[gnu::always_inline]] static StrutRow Zero() { return StrutRow(); }
  [[gnu::always_inline]] double& operator[](int j) { return values_[j]; }
  [[gnu::always_inline]] double operator[](int j) const { return values_[j]; }

  [[gnu::always_inline]] friend StrutRow operator+(const StrutRow& a, const StrutRow& b) {
    return a.map(b, [](Lane x, Lane y) { return x + y; });
  }
  [[gnu::always_inline]] friend StrutRow operator-(const StrutRow& a, const StrutRow& b) {
    return a.map(b, [](Lane x, Lane y) { return x - y; });
  }
  [[gnu::always_inline]] friend StrutRow operator*(const StrutRow& a, const StrutRow& b) {
    return a.map(b, [](Lane x, Lane y) { return x * y; });
  }
  [[gnu::always_inline]] friend StrutRow operator/(const StrutRow& a, const StrutRow& b) {
    return a.map(b, [](Lane x, Lane y) { return x / y; });
  }
  [[gnu::always_inline]] friend StrutRow operator+(const StrutRow& a, double s) { return a + constant(s); }
  [[gnu::always_inline]] friend StrutRow operator*(double s, const StrutRow& a) { return constant(s) * a; }
  [[gnu::always_inline]] friend StrutRow operator*(const StrutRow& a, double s) { return a * constant(s); }

  [[gnu::always_inline]] StrutRow square() const { return *this * *this; }
  [[gnu::always_inline]] StrutRow inverse() const { return constant(1.0) / *this; }
  [[gnu::always_inline]] StrutRow sqrt() const {
    StrutRow r;
    for (int j = 0; j < kMaxActuators; ++j) r.values_[j] = std::sqrt(values_[j]);
    return r;
  }
  [[gnu::always_inline]] double sum() const {
    Lane total = lanes_[0];
    for (int q = 1; q < kLanes; ++q) total += lanes_[q];
    return total[0] + total[1];
  }

 private:
  [[gnu::always_inline]] static StrutRow constant(double s) {
    StrutRow r;
    for (int q = 0; q < kLanes; ++q) r.lanes_[q] = Lane{s, s};
    return r;
  }
  template <class Operation>
  [[gnu::always_inline]] StrutRow map(const StrutRow& b, Operation operation) const {
    StrutRow r;
    for (int q = 0; q < kLanes; ++q) r.lanes_[q] = operation(lanes_[q], b.lanes_[q]);
    return r;
  }

  // The same storage seen as pairs (the arithmetic) and as doubles (one strut's value): reading a union
  // member other than the one last written is defined by GCC and Clang.
  union {
    Lane lanes_[kLanes] = {};
    double values_[2 * kLanes];
  };
};

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
