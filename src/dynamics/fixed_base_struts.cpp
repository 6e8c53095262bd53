#include "dynamics/fixed_base_struts.hpp"

#include "core/wide_kernels.hpp"

namespace pkm::dynamics {
namespace {

using Row = StrutRow;
using Rows3 = StrutRows3;

// Forced inline: returned out of line, each 3-row result goes through memory (about 240 instructions per
// right-hand side in calls and copies, callgrind).
[[gnu::always_inline]] inline Rows3 cross(const Eigen::Vector3d& a, const Rows3& b) {
  return {a.y() * b.z - a.z() * b.y, a.z() * b.x - a.x() * b.z, a.x() * b.y - a.y() * b.x};
}
[[gnu::always_inline]] inline Rows3 cross(const Rows3& a, const Rows3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Row dot(const Rows3& a, const Rows3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Row dot(const Rows3& a, const Eigen::Vector3d& b) {
  return a.x * b.x() + a.y * b.y() + a.z * b.z();
}
Eigen::Vector3d sums(const Rows3& a) {
  return {a.x.sum(), a.y.sum(), a.z.sum()};
}

inline void add_struts(const MechanismState& state, const DynamicsParameters& parameters, const Twist& twist,
                       MassLowerTriangle& mass, Twist& bias, Twist& applied) {
  // The state's rows: the joints' arms from the tool point, the unit directions, 1/L, and each strut's
  // constants m_u, m_u c_u, m_l c_l and J = m_l c_l² + m_u c_u² + I_t (the turning inertia about the base
  // joint), zero in the lanes of struts on moving base joints.
  const Rows3& arm = state.strut_arm_rows_mm;
  const Rows3& u = state.strut_u_rows;
  const Row& inverse_length = state.strut_inverse_length_per_mm;
  const FixedBaseStrutConstants& constants = state.fixed_base_constants;
  const Row& upper_mass = constants.upper_kg;
  const Row& upper_moment = constants.upper_moment_kg_mm;
  const Row& lower_moment = constants.lower_moment_kg_mm;
  const Row& turning = constants.turning_kg_mm2;
  // A fixed base joint (W = 0): U = P/L, and with [u]× P = [u]× and (I − aP)ᵀ(I − aP) = uuᵀ + (1 − a)² P,
  // S = m_u uuᵀ + σ P, σ = m_l (c_l/L)² + m_u (1 − c_u/L)² + I_t/L² = J/L² + m_u − 2 m_u c_u/L, κ = m_u − σ.
  const Row sigma = turning * inverse_length.square() + upper_mass - 2.0 * upper_moment * inverse_length;
  const Row kappa = upper_mass - sigma;

  // Mass matrix: σ GᵀG by its sums, and the rank-one κ j jᵀ, j = (u, n), n = arm × u.
  const Rows3 sigma_arm{sigma * arm.x, sigma * arm.y, sigma * arm.z};
  mass.sigma += sigma.sum();
  mass.sigma_arm += sums(sigma_arm);
  mass.sigma_square += dot(sigma_arm, arm).sum();
  const Row* const sigma_arm_rows[3] = {&sigma_arm.x, &sigma_arm.y, &sigma_arm.z};
  const Row* const arm_rows[3] = {&arm.x, &arm.y, &arm.z};
  for (int c = 0; c < 3; ++c) {
    for (int r = c; r < 3; ++r) mass.lower(3 + r, 3 + c) -= (*sigma_arm_rows[r] * *arm_rows[c]).sum();
  }
  const Rows3 n = cross(arm, u);
  const Row* const j_rows[6] = {&u.x, &u.y, &u.z, &n.x, &n.y, &n.z};
  for (int c = 0; c < 6; ++c) {
    const Row weighted = kappa * *j_rows[c];
    for (int r = c; r < 6; ++r) mass.lower(r, c) += (weighted * *j_rows[r]).sum();
  }

  // The joints' velocities and accelerations at zero twist rate: ḃ = v + ω × arm, b̈ = ω × (ω × arm).
  const Eigen::Vector3d v = twist.head<3>(), w = twist.tail<3>();
  const Rows3 turning_velocity = cross(w, arm);
  const Rows3 b_v{turning_velocity.x + v.x(), turning_velocity.y + v.y(), turning_velocity.z + v.z()};
  const Rows3 b_a = cross(w, turning_velocity);
  // The parts' rates of momentum carried back to the joint (lower part m_l c_l ü, upper part
  // m_u (b̈ − c_u ü), turn I_t u × ü, through Pᵀ = P and turnᵀ τ = τ × u / L) collect, with
  // ü = (P b̈ − 2 L̇ u̇)/L − |u̇|² u (u·ü = −|u̇|²), into
  //   S b̈ + m_u c_u |u̇|² u − 2 (m_u c_u/L − κ) L̇ u̇:
  // the mass-matrix term at the joint's acceleration plus the struts' centripetal and Coriolis parts.
  const Row length_rate = dot(u, b_v);
  const Rows3 u_rate{(b_v.x - length_rate * u.x) * inverse_length,
                     (b_v.y - length_rate * u.y) * inverse_length,
                     (b_v.z - length_rate * u.z) * inverse_length};
  const Row along = kappa * dot(u, b_a) + upper_moment * dot(u_rate, u_rate);
  const Row across = 2.0 * (upper_moment * inverse_length - kappa) * length_rate;
  const Rows3 momentum{sigma * b_a.x + along * u.x - across * u_rate.x,
                       sigma * b_a.y + along * u.y - across * u_rate.y,
                       sigma * b_a.z + along * u.z - across * u_rate.z};
  bias.head<3>() += sums(momentum);
  bias.tail<3>() += sums(cross(arm, momentum));

  // The weights the same way: m_u g + ((m_l c_l − m_u c_u)/L) P g = (m_u + a) g − a (u·g) u; about the tool
  // point, (Σ (m_u + a) arm) × g − Σ a (u·g) n.
  const Eigen::Vector3d& gravity = parameters.gravity_mm_s2;
  const Row across_weight = (lower_moment - upper_moment) * inverse_length;
  const Row along_gravity = upper_mass + across_weight;
  const Row down_strut = across_weight * dot(u, gravity);
  const Eigen::Vector3d down_strut_sum = sums({down_strut * u.x, down_strut * u.y, down_strut * u.z});
  const Eigen::Vector3d weighted_arm =
      sums({along_gravity * arm.x, along_gravity * arm.y, along_gravity * arm.z});
  applied.head<3>() += along_gravity.sum() * gravity - down_strut_sum;
  applied.tail<3>() +=
      weighted_arm.cross(gravity) - sums({down_strut * n.x, down_strut * n.y, down_strut * n.z});
}

#if PKM_HAS_WIDE_KERNELS
// The same compiled for AVX2 with fused multiply–add (core/wide_kernels.hpp).
PKM_WIDE_KERNEL void add_struts_wide(const MechanismState& state, const DynamicsParameters& parameters,
                                     const Twist& twist, MassLowerTriangle& mass, Twist& bias,
                                     Twist& applied) {
  add_struts(state, parameters, twist, mass, bias, applied);
}
#endif

}  // namespace

void add_fixed_base_struts(const MechanismState& state, const DynamicsParameters& parameters,
                           const Twist& twist, MassLowerTriangle& mass, Twist& bias, Twist& applied) {
#if PKM_HAS_WIDE_KERNELS
  if (wide_kernels_enabled()) return add_struts_wide(state, parameters, twist, mass, bias, applied);
#endif
  add_struts(state, parameters, twist, mass, bias, applied);
}

}  // namespace pkm::dynamics
