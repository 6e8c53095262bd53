#include "dynamics/rigid_terms.hpp"

#include "core/rotation.hpp"
#include "core/wide_kernels.hpp"
#include "dynamics/fixed_base_struts.hpp"
#include "dynamics/mass_lower_triangle.hpp"

namespace pkm::dynamics {
namespace {

/// Adds the lower triangle of Gᵀ S G, G = [I, −X] with X = [arm]× (so Gᵀ = [I; X]), for a symmetric S, to
/// `lower` (MassLowerTriangle: its upper triangle is neither set nor read).
void add_joint_block(const Eigen::Matrix3d& s, const Eigen::Matrix3d& x, Matrix6& lower) {
  const Eigen::Matrix3d xs = x * s;
  lower.topLeftCorner<3, 3>().triangularView<Eigen::Lower>() += s;
  lower.bottomLeftCorner<3, 3>() += xs;
  lower.bottomRightCorner<3, 3>().triangularView<Eigen::Lower>() -= xs * x;
}

/// Adds Gᵀ f = (f, arm × f) to the 6-vector `g`.
inline void add_joint_force(const Eigen::Vector3d& f, const Eigen::Vector3d& arm, Twist& g) {
  g.head<3>() += f;
  g.tail<3>() += arm.cross(f);
}

inline void terms_in_twist(const MechanismState& state, const DynamicsParameters& parameters,
                           const Twist& twist, const statics::Wrench& load, TwistRigidTerms& out) {
  const Eigen::Vector3d v = twist.head<3>(), w = twist.tail<3>();
  const Eigen::Vector3d& gravity = parameters.gravity_mm_s2;
  Twist& bias = out.bias;
  Twist& applied = out.applied;
  bias.setZero();
  applied << load.force_N * 1e3, load.moment_Nmm * 1e3;  // N → kg·mm/s²

  // The platform: v_c = v + ω × r, so G = [I, −[r]×]; a_c = ω × (ω × r) at zero twist rate; Euler's ω × Iω.
  const Eigen::Vector3d& r = state.platform_arm_mm;
  const Eigen::Matrix3d& inertia = state.platform_inertia_kg_mm2;
  MassLowerTriangle& mass = out.mass;
  mass.clear();
  mass.add_point(state.platform_kg, r);
  mass.lower.bottomRightCorner<3, 3>().triangularView<Eigen::Lower>() += inertia;
  add_joint_force(state.platform_kg * w.cross(w.cross(r)), r, bias);
  bias.tail<3>() += w.cross(inertia * w);
  add_joint_force(state.platform_kg * gravity, r, applied);

  add_fixed_base_struts(state, parameters, twist, mass, bias, applied);

  // The struts whose base joints move: each carriage on its guide, strut by strut.
  for (int j = 0; j < state.struts; ++j) {
    if (!state.base_moves[j]) continue;
    const StrutDynamics& p = parameters.struts[j];
    const Eigen::Vector3d arm = state.ends.platform_mm[j] - state.pose.position_mm;
    const double length = state.strut_length_mm[j];
    const Eigen::Vector3d& u = state.strut_u[j];
    // The joint's velocity and acceleration at zero twist rate.
    const Eigen::Vector3d b_v = v + w.cross(arm);
    const Eigen::Vector3d b_a = w.cross(w.cross(arm));
    const double transverse = p.lower.transverse_inertia_kg_mm2 + p.upper.transverse_inertia_kg_mm2;
    const Eigen::Vector3d& first = state.base_first[j];
    const Eigen::Vector3d d = length * u;
    const double along = d.dot(first);
    const Eigen::Matrix3d carriage = first * d.transpose() / along;  // W
    const double q_rate = d.dot(b_v) / along;
    const Eigen::Vector3d base_v = first * q_rate;
    // |B − A(q)|² = const, twice differentiated (as body_motion.cpp).
    const double q_accel =
        (d.dot(b_a) - d.dot(state.base_second[j]) * q_rate * q_rate + (b_v - base_v).squaredNorm()) / along;
    const Eigen::Vector3d base_a = first * q_accel + state.base_second[j] * q_rate * q_rate;
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - u * u.transpose();            // P
    const Eigen::Matrix3d u_map = across * (Eigen::Matrix3d::Identity() - carriage) / length;  // U
    const Eigen::Matrix3d lower = carriage + p.lower.com_mm * u_map;
    const Eigen::Matrix3d upper = Eigen::Matrix3d::Identity() - p.upper.com_mm * u_map;
    const Eigen::Matrix3d turn = skew(u) * u_map;
    const Eigen::Matrix3d s =
        p.lower.mass_kg * lower.transpose() * lower + p.upper.mass_kg * upper.transpose() * upper +
        transverse * turn.transpose() * turn + p.carriage_kg * carriage.transpose() * carriage;
    add_joint_block(s, skew(arm), mass.lower);

    // The strut's direction rates: d = L u ⇒ ḋ = L̇ u + L u̇, d̈ = L̈ u + 2 L̇ u̇ + L ü (body_motion.cpp).
    const Eigen::Vector3d d_rate = b_v - base_v, d_accel = b_a - base_a;
    const double length_rate = u.dot(d_rate);
    const Eigen::Vector3d u_rate = (d_rate - length_rate * u) / length;
    const double length_accel = u.dot(d_accel) + length * u_rate.squaredNorm();
    const Eigen::Vector3d u_accel = (d_accel - length_accel * u - 2.0 * length_rate * u_rate) / length;
    // Rates of momentum (axisymmetric parts turning across their axis: I_t α, α = u × ü), carried back.
    const Eigen::Vector3d momentum =
        lower.transpose() * (p.lower.mass_kg * (base_a + p.lower.com_mm * u_accel)) +
        upper.transpose() * (p.upper.mass_kg * (b_a - p.upper.com_mm * u_accel)) +
        turn.transpose() * (transverse * u.cross(u_accel)) + carriage.transpose() * (p.carriage_kg * base_a);
    add_joint_force(momentum, arm, bias);
    const Eigen::Vector3d weight =
        (p.lower.mass_kg * lower + p.upper.mass_kg * upper + p.carriage_kg * carriage).transpose() * gravity;
    add_joint_force(weight, arm, applied);
  }
  mass.fold_sums();
}

#if PKM_HAS_WIDE_KERNELS
// The same compiled for AVX2 with fused multiply–add (core/wide_kernels.hpp).
PKM_WIDE_KERNEL void terms_in_twist_wide(const MechanismState& state, const DynamicsParameters& parameters,
                                         const Twist& twist, const statics::Wrench& load,
                                         TwistRigidTerms& out) {
  terms_in_twist(state, parameters, twist, load, out);
}
#endif

}  // namespace

void twist_rigid_terms(const MechanismState& state, const DynamicsParameters& parameters, const Twist& twist,
                       const statics::Wrench& load, TwistRigidTerms& out) {
#if PKM_HAS_WIDE_KERNELS
  if (wide_kernels_enabled()) return terms_in_twist_wide(state, parameters, twist, load, out);
#endif
  terms_in_twist(state, parameters, twist, load, out);
}

void rigid_terms(const MechanismState& state, const DynamicsParameters& parameters, const TwistBasis& basis,
                 const Twist& twist, const statics::Wrench& load, RigidTerms& out) {
  TwistRigidTerms terms;
  twist_rigid_terms(state, parameters, twist, load, terms);
  if (basis.cols() == 6 && basis.isIdentity(0.0)) {  // the free platform's own twist: no projection
    terms.mass.write_full(out.mass);
    out.bias = terms.bias;
    out.applied = terms.applied;
    return;
  }
  Matrix6 full_mass;
  terms.mass.write_full(full_mass);
  out.mass = basis.transpose() * full_mass * basis;
  out.bias = basis.transpose() * terms.bias;
  out.applied = basis.transpose() * terms.applied;
}

}  // namespace pkm::dynamics
