#include "dynamics/rigid_terms.hpp"

#include "core/rotation.hpp"

namespace pkm::dynamics {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Adds Gᵀ S G, G = [I, −X] with X = [arm]× (so Gᵀ = [I; X]), to the 6 × 6 `m`.
void add_joint_block(const Eigen::Matrix3d& s, const Eigen::Matrix3d& x, Matrix6& m) {
  const Eigen::Matrix3d sx = s * x;
  m.topLeftCorner<3, 3>() += s;
  m.topRightCorner<3, 3>() -= sx;
  m.bottomLeftCorner<3, 3>() += x * s;
  m.bottomRightCorner<3, 3>() -= x * sx;
}

/// Σ_j G_jᵀ S_j G_j for struts on fixed base joints, where S = σ I + κ u uᵀ: Σ σ GᵀG (GᵀG = [I, −X; X, −X²],
/// X = [arm]×, −X² = |arm|² I − arm armᵀ) plus the rank-one terms κ j jᵀ with j = (u, n), n = arm × u (from
/// S X = σ X − κ u nᵀ and X S X = σ X² − κ n nᵀ). Gathered strut by strut in 3 × 3 blocks (small fixed
/// products Eigen writes out in place), added once.
struct FixedJointBlocks {
  double sigma = 0.0, sigma_square = 0.0;  // Σ σ, Σ σ |arm|²
  Eigen::Vector3d sigma_arm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sigma_outer = Eigen::Matrix3d::Zero();  // Σ σ arm armᵀ
  Eigen::Matrix3d uu = Eigen::Matrix3d::Zero(), un = Eigen::Matrix3d::Zero(), nn = Eigen::Matrix3d::Zero();

  /// σ GᵀG for a body whose velocity is that of the point at `arm` (the platform: σ = m, no rank-one part).
  void add_point(double s, const Eigen::Vector3d& arm) {
    sigma += s;
    const Eigen::Vector3d weighted = s * arm;
    sigma_arm += weighted;
    sigma_square += weighted.dot(arm);
    sigma_outer.noalias() += weighted * arm.transpose();
  }
  void add(double s, double kappa, const Eigen::Vector3d& u, const Eigen::Vector3d& arm) {
    add_point(s, arm);
    const Eigen::Vector3d n = arm.cross(u);
    const Eigen::Vector3d weighted_u = kappa * u;
    uu.noalias() += weighted_u * u.transpose();
    un.noalias() += weighted_u * n.transpose();
    nn.noalias() += (kappa * n) * n.transpose();
  }
  void add_to(Matrix6& m) const {
    const Eigen::Matrix3d x = skew(sigma_arm);
    m.topLeftCorner<3, 3>() += uu;
    m.topLeftCorner<3, 3>().diagonal().array() += sigma;
    m.topRightCorner<3, 3>() += un - x;
    m.bottomLeftCorner<3, 3>() += un.transpose() + x;
    m.bottomRightCorner<3, 3>() += nn - sigma_outer;
    m.bottomRightCorner<3, 3>().diagonal().array() += sigma_square;
  }
};

/// Adds Gᵀ f = (f, arm × f) to the 6-vector `g`.
inline void add_joint_force(const Eigen::Vector3d& f, const Eigen::Vector3d& arm, Twist& g) {
  g.head<3>() += f;
  g.tail<3>() += arm.cross(f);
}

}  // namespace

void rigid_terms(const MechanismState& state, const DynamicsParameters& parameters, const TwistBasis& basis,
                 const Twist& twist, const statics::Wrench& load, RigidTerms& out) {
  const Eigen::Vector3d v = twist.head<3>(), w = twist.tail<3>();
  const Eigen::Vector3d& gravity = parameters.gravity_mm_s2;
  Matrix6 mass = Matrix6::Zero();
  Twist bias = Twist::Zero(), applied;
  applied << load.force_N * 1e3, load.moment_Nmm * 1e3;  // N → kg·mm/s²

  // The platform: v_c = v + ω × r, so G = [I, −[r]×]; a_c = ω × (ω × r) at zero twist rate; Euler's ω × Iω.
  const Eigen::Vector3d& r = state.platform_arm_mm;
  const Eigen::Matrix3d& inertia = state.platform_inertia_kg_mm2;
  FixedJointBlocks fixed;
  fixed.add_point(state.platform_kg, r);
  mass.bottomRightCorner<3, 3>() += inertia;
  add_joint_force(state.platform_kg * w.cross(w.cross(r)), r, bias);
  bias.tail<3>() += w.cross(inertia * w);
  add_joint_force(state.platform_kg * gravity, r, applied);

  // The fixed-base struts' rates of momentum and weights carried to their joints: Σ f and Σ arm × f.
  Eigen::Vector3d joint_momentum_sum = Eigen::Vector3d::Zero(),
                  joint_momentum_moment = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_weight_sum = Eigen::Vector3d::Zero(), joint_weight_moment = Eigen::Vector3d::Zero();
  for (int j = 0; j < state.struts; ++j) {
    const StrutDynamics& p = parameters.struts[j];
    const Eigen::Vector3d& b = state.ends.platform_mm[j];
    const Eigen::Vector3d arm = b - state.pose.position_mm;
    const double length = state.strut_length_mm[j], inverse_length = 1.0 / length;
    const Eigen::Vector3d& u = state.strut_u[j];
    // The joint's velocity and acceleration at zero twist rate.
    const Eigen::Vector3d b_v = v + w.cross(arm);
    const Eigen::Vector3d b_a = w.cross(w.cross(arm));
    const double transverse = p.lower.transverse_inertia_kg_mm2 + p.upper.transverse_inertia_kg_mm2;
    if (!state.base_moves[j]) {
      // A fixed base joint (W = 0): U = P/L, and with [u]× P = [u]× and (I − aP)ᵀ(I − aP) = uuᵀ + (1 − a)² P,
      // S = m_u uuᵀ + σ P, σ = m_l (c_l/L)² + m_u (1 − c_u/L)² + I_t/L² = J/L² + m_u − 2 m_u c_u/L with
      // the shorthand J = m_l c_l² + m_u c_u² + I_t, and κ = m_u − σ.
      const double upper_moment = p.upper.mass_kg * p.upper.com_mm;  // m_u c_u
      const double turning = p.lower.mass_kg * p.lower.com_mm * p.lower.com_mm +
                             upper_moment * p.upper.com_mm + transverse;  // J
      const double sigma =
          turning * inverse_length * inverse_length + p.upper.mass_kg - 2.0 * upper_moment * inverse_length;
      const double kappa = p.upper.mass_kg - sigma;
      fixed.add(sigma, kappa, u, arm);
      // The parts' rates of momentum carried back to the joint (lower part m_l c_l ü, upper part
      // m_u (b̈ − c_u ü), turn I_t u × ü, through Pᵀ = P and turnᵀ τ = τ × u / L) collect, with
      // ü = (P b̈ − 2 L̇ u̇)/L − |u̇|² u (u·ü = −|u̇|²), into
      //   S b̈ + m_u c_u |u̇|² u − 2 (m_u c_u/L − κ) L̇ u̇:
      // the mass-matrix term at the joint's acceleration plus the struts' centripetal and Coriolis parts.
      const double length_rate = u.dot(b_v);
      const Eigen::Vector3d u_rate = (b_v - length_rate * u) * inverse_length;
      const Eigen::Vector3d joint_momentum =
          sigma * b_a + (kappa * u.dot(b_a) + upper_moment * u_rate.squaredNorm()) * u -
          (2.0 * (upper_moment * inverse_length - kappa) * length_rate) * u_rate;
      joint_momentum_sum += joint_momentum;
      joint_momentum_moment += arm.cross(joint_momentum);
      // The weights the same way: m_u g + ((m_l c_l − m_u c_u)/L) P g.
      const double across_weight = (p.lower.mass_kg * p.lower.com_mm - upper_moment) * inverse_length;
      const Eigen::Vector3d joint_weight =
          p.upper.mass_kg * gravity + across_weight * (gravity - u.dot(gravity) * u);
      joint_weight_sum += joint_weight;
      joint_weight_moment += arm.cross(joint_weight);
      continue;
    }
    // A carriage on its guide.
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
    add_joint_block(s, skew(arm), mass);

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
  fixed.add_to(mass);
  bias.head<3>() += joint_momentum_sum;
  bias.tail<3>() += joint_momentum_moment;
  applied.head<3>() += joint_weight_sum;
  applied.tail<3>() += joint_weight_moment;
  if (basis.cols() == 6 && basis.isIdentity(0.0)) {  // the free platform's own twist: no projection
    out.mass = mass;
    out.bias = bias;
    out.applied = applied;
    return;
  }
  out.mass = basis.transpose() * mass * basis;
  out.bias = basis.transpose() * bias;
  out.applied = basis.transpose() * applied;
}

}  // namespace pkm::dynamics
