#include "dynamics/body_motion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pkm::dynamics {
namespace {

/// The platform and its payload as one body: mass, CoM in the tool frame, inertia about that CoM (platform
/// axes), by the parallel-axis theorem.
void combine_platform(const DynamicsParameters& parameters, double& mass_kg, Eigen::Vector3d& com_mm,
                      Eigen::Matrix3d& inertia_kg_mm2) {
  const BodyInertia* bodies[] = {&parameters.platform, &parameters.payload};
  mass_kg = 0.0;
  com_mm.setZero();
  for (const BodyInertia* b : bodies) {
    mass_kg += b->mass_kg;
    com_mm += b->mass_kg * b->com_mm;
  }
  if (mass_kg > 0.0) com_mm /= mass_kg;
  inertia_kg_mm2.setZero();
  for (const BodyInertia* b : bodies) {
    const Eigen::Vector3d r = b->com_mm - com_mm;
    inertia_kg_mm2 +=
        b->inertia_kg_mm2 + b->mass_kg * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
}

/// d = B − A = L u and its derivatives → the strut's direction rates and its angular velocity and
/// acceleration (perpendicular to the axis): ḋ = L̇ u + L u̇, d̈ = L̈ u + 2 L̇ u̇ + L ü, ω = u × u̇, α = u × ü.
/// Without `accelerations` (a virtual motion) only the rates.
StrutMotion strut_motion(const Eigen::Vector3d& u, double length, const Eigen::Vector3d& d_rate,
                         const Eigen::Vector3d& d_accel, bool accelerations) {
  StrutMotion s;
  s.u = u;
  const double inverse_length = 1.0 / length;
  const double length_rate = u.dot(d_rate);
  s.u_rate = (d_rate - length_rate * u) * inverse_length;
  s.omega = u.cross(s.u_rate);
  if (accelerations) {
    const double length_accel = u.dot(d_accel) + length * s.u_rate.squaredNorm();
    s.u_accel = (d_accel - length_accel * u - 2.0 * length_rate * s.u_rate) * inverse_length;
    s.alpha = u.cross(s.u_accel);
  }
  return s;
}

BodyMotion motion_of(const MechanismState& state, const DynamicsParameters& parameters,
                     const Eigen::Matrix<double, 6, 1>& twist, const Eigen::Matrix<double, 6, 1>& twist_rate,
                     bool accelerations) {
  BodyMotion m;
  m.struts = state.struts;
  const Eigen::Vector3d v = twist.head<3>(), w = twist.tail<3>();
  const Eigen::Vector3d a = twist_rate.head<3>(), alpha = twist_rate.tail<3>();
  m.omega = w;
  m.alpha = alpha;
  const Eigen::Vector3d& r = state.platform_arm_mm;
  m.platform_v = v + w.cross(r);
  if (accelerations) m.platform_a = a + alpha.cross(r) + w.cross(w.cross(r));
  for (int j = 0; j < state.struts; ++j) {
    const Eigen::Vector3d arm = state.ends.platform_mm[j] - state.pose.position_mm;
    const Eigen::Vector3d b_v = v + w.cross(arm);
    const Eigen::Vector3d b_a = accelerations ? Eigen::Vector3d(a + alpha.cross(arm) + w.cross(w.cross(arm)))
                                              : Eigen::Vector3d::Zero();
    const Eigen::Vector3d d = state.ends.platform_mm[j] - state.ends.base_mm[j];
    Eigen::Vector3d base_v = Eigen::Vector3d::Zero(), base_a = Eigen::Vector3d::Zero();
    if (state.base_moves[j]) {
      // A strut of constant length on a moving base joint: |B − A(q)|² = L² differentiated once and twice
      // gives the carriage's rate and acceleration.
      const Eigen::Vector3d& first = state.base_first[j];
      const double along = d.dot(first);
      const double q_rate = d.dot(b_v) / along;
      base_v = first * q_rate;
      if (accelerations) {
        const Eigen::Vector3d d_rate = b_v - base_v;
        const double q_accel =
            (d.dot(b_a) - d.dot(state.base_second[j]) * q_rate * q_rate + d_rate.squaredNorm()) / along;
        base_a = first * q_accel + state.base_second[j] * q_rate * q_rate;
      }
    }
    const StrutMotion s =
        strut_motion(state.strut_u[j], state.strut_length_mm[j], b_v - base_v, b_a - base_a, accelerations);
    m.strut[j] = s;
    m.base_v[j] = base_v;
    m.base_a[j] = base_a;
    const StrutDynamics& p = parameters.struts[j];
    m.lower_v[j] = base_v + p.lower.com_mm * s.u_rate;
    m.upper_v[j] = b_v - p.upper.com_mm * s.u_rate;
    m.lower_a[j] = base_a + p.lower.com_mm * s.u_accel;
    m.upper_a[j] = b_a - p.upper.com_mm * s.u_accel;
  }
  return m;
}

}  // namespace

int set_strut_directions(MechanismState& state) {
  const int n = state.struts;
  StrutRows3& arm = state.strut_arm_rows_mm;
  StrutRows3 d;  // B − A: gathered into rows, so that the roots and divisions take two struts at once
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d& platform = state.ends.platform_mm[j];
    const Eigen::Vector3d& base = state.ends.base_mm[j];
    arm.x[j] = platform.x() - state.pose.position_mm.x();
    arm.y[j] = platform.y() - state.pose.position_mm.y();
    arm.z[j] = platform.z() - state.pose.position_mm.z();
    d.x[j] = platform.x() - base.x();
    d.y[j] = platform.y() - base.y();
    d.z[j] = platform.z() - base.z();
  }
  for (int j = n; j < kMaxActuators; ++j) arm.x[j] = arm.y[j] = arm.z[j] = 0.0;
  StrutRow length = (d.x * d.x + d.y * d.y + d.z * d.z).sqrt();
  for (int j = 0; j < n; ++j) {
    if (!(length[j] > 0.0)) return j;
  }
  for (int j = n; j < kMaxActuators; ++j) length[j] = 1.0;  // no strut: zero direction, 1/L set to zero below
  StrutRows3& u = state.strut_u_rows;
  u.x = d.x / length;
  u.y = d.y / length;
  u.z = d.z / length;
  state.strut_inverse_length_per_mm = length.inverse();
  for (int j = n; j < kMaxActuators; ++j) state.strut_inverse_length_per_mm[j] = 0.0;
  for (int j = 0; j < n; ++j) {
    state.strut_length_mm[j] = length[j];
    state.strut_u[j] = Eigen::Vector3d(u.x[j], u.y[j], u.z[j]);
  }
  return -1;
}

void set_fixed_base_constants(const FixedBaseStrutConstants& constants, MechanismState& state) {
  FixedBaseStrutConstants& c = state.fixed_base_constants;
  c = constants;
  for (int j = 0; j < state.struts; ++j) {
    if (!state.base_moves[j]) continue;
    c.upper_kg[j] = c.upper_moment_kg_mm[j] = c.lower_moment_kg_mm[j] = c.turning_kg_mm2[j] = 0.0;
  }
}

Status mechanism_state(const Mechanism& mechanism, const DynamicsParameters& parameters, const Pose& pose,
                       MechanismState& state) {
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  state.pose = *completed;
  const int n = mechanism.actuator_count();
  if (parameters.strut_count != 0 && parameters.strut_count != n) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("dynamics: {} struts described for a mechanism with {} actuators",
                                  parameters.strut_count, n));
  }
  state.struts = mechanism.strut_ends(state.pose, state.ends);
  if (state.struts < 0 || !mechanism.actuator_values(state.pose, state.actuators.data())) {
    return make_error(ErrorCode::unreachable, "dynamics: the pose is out of reach");
  }
  if (const int zero = set_strut_directions(state); zero >= 0) {
    return make_error(ErrorCode::singular, fmt::format("dynamics: strut {} has zero length", zero + 1));
  }
  for (int j = 0; j < state.struts; ++j) {
    mechanism.base_joint_motion(j, state.actuators[j], state.base_first[j], state.base_second[j]);
    state.base_moves[j] = state.base_first[j].squaredNorm() > 0.0;
    if (state.base_moves[j] &&
        !(std::abs((state.ends.platform_mm[j] - state.ends.base_mm[j]).dot(state.base_first[j])) > 0.0)) {
      return make_error(ErrorCode::singular,
                        fmt::format("dynamics: strut {} is perpendicular to its carriage's path", j + 1));
    }
  }
  if (!mechanism.twist_jacobian(state.pose, state.twist_jacobian) ||
      !mechanism.controlled_twists(state.pose, state.basis)) {
    return make_error(
        ErrorCode::unsupported,
        "dynamics: the mechanism gives no twist Jacobian at this pose (out of reach or singular)");
  }
  set_fixed_base_constants(fixed_base_strut_constants(parameters, state.struts), state);
  Eigen::Vector3d com_tool;
  Eigen::Matrix3d inertia_tool;
  combine_platform(parameters, state.platform_kg, com_tool, inertia_tool);
  state.platform_arm_mm = state.pose.rotation * com_tool;
  state.platform_inertia_kg_mm2 = state.pose.rotation * inertia_tool * state.pose.rotation.transpose();
  return ok_status();
}

BodyMotion body_motion(const MechanismState& state, const DynamicsParameters& parameters,
                       const Eigen::Matrix<double, 6, 1>& twist,
                       const Eigen::Matrix<double, 6, 1>& twist_rate) {
  return motion_of(state, parameters, twist, twist_rate, true);
}

BodyMotion body_velocities(const MechanismState& state, const DynamicsParameters& parameters,
                           const Eigen::Matrix<double, 6, 1>& twist) {
  return motion_of(state, parameters, twist, Eigen::Matrix<double, 6, 1>::Zero(), false);
}

BodyMomentumRates momentum_rates(const MechanismState& state, const DynamicsParameters& parameters,
                                 const BodyMotion& motion) {
  BodyMomentumRates r;
  r.struts = state.struts;
  const Eigen::Matrix3d& inertia = state.platform_inertia_kg_mm2;
  r.platform_force = state.platform_kg * motion.platform_a;
  r.platform_moment = inertia * motion.alpha + motion.omega.cross(inertia * motion.omega);
  for (int j = 0; j < state.struts; ++j) {
    const StrutDynamics& p = parameters.struts[j];
    r.lower_force[j] = p.lower.mass_kg * motion.lower_a[j];
    r.upper_force[j] = p.upper.mass_kg * motion.upper_a[j];
    r.carriage_force[j] = p.carriage_kg * motion.base_a[j];
    // Axisymmetric parts turning perpendicular to their axis: H = I_t ω with ω ⊥ u, and α = u × ü ⊥ u, so
    // dH/dt = I_t α (the ω × Iω term vanishes for ω along a principal axis of equal moments).
    r.strut_moment[j] =
        (p.lower.transverse_inertia_kg_mm2 + p.upper.transverse_inertia_kg_mm2) * motion.strut[j].alpha;
  }
  return r;
}

double power(const BodyMomentumRates& rates, const BodyMotion& velocities) {
  double p = rates.platform_force.dot(velocities.platform_v) + rates.platform_moment.dot(velocities.omega);
  for (int j = 0; j < std::min(rates.struts, velocities.struts); ++j) {
    p += rates.lower_force[j].dot(velocities.lower_v[j]) + rates.upper_force[j].dot(velocities.upper_v[j]) +
         rates.carriage_force[j].dot(velocities.base_v[j]) +
         rates.strut_moment[j].dot(velocities.strut[j].omega);
  }
  return p;
}

double gravity_power(const MechanismState& state, const DynamicsParameters& parameters,
                     const BodyMotion& velocities, const Eigen::Vector3d& gravity_mm_s2) {
  double p = state.platform_kg * gravity_mm_s2.dot(velocities.platform_v);
  for (int j = 0; j < state.struts; ++j) {
    const StrutDynamics& s = parameters.struts[j];
    p += gravity_mm_s2.dot(s.lower.mass_kg * velocities.lower_v[j] + s.upper.mass_kg * velocities.upper_v[j] +
                           s.carriage_kg * velocities.base_v[j]);
  }
  return p;
}

double kinetic_energy(const MechanismState& state, const DynamicsParameters& parameters,
                      const BodyMotion& velocities) {
  double t = state.platform_kg * velocities.platform_v.squaredNorm() +
             velocities.omega.dot(state.platform_inertia_kg_mm2 * velocities.omega);
  for (int j = 0; j < state.struts; ++j) {
    const StrutDynamics& s = parameters.struts[j];
    t += s.lower.mass_kg * velocities.lower_v[j].squaredNorm() +
         s.upper.mass_kg * velocities.upper_v[j].squaredNorm() +
         s.carriage_kg * velocities.base_v[j].squaredNorm() +
         (s.lower.transverse_inertia_kg_mm2 + s.upper.transverse_inertia_kg_mm2) *
             velocities.strut[j].omega.squaredNorm();
  }
  return 0.5 * t;
}

double gravity_potential(const MechanismState& state, const DynamicsParameters& parameters) {
  const Eigen::Vector3d& g = parameters.gravity_mm_s2;
  double v = -state.platform_kg * g.dot(state.pose.position_mm + state.platform_arm_mm);
  for (int j = 0; j < state.struts; ++j) {
    const StrutDynamics& s = parameters.struts[j];
    const Eigen::Vector3d& a = state.ends.base_mm[j];
    const Eigen::Vector3d& b = state.ends.platform_mm[j];
    const Eigen::Vector3d u = (b - a).normalized();
    v -= g.dot(s.lower.mass_kg * (a + s.lower.com_mm * u) + s.upper.mass_kg * (b - s.upper.com_mm * u) +
               s.carriage_kg * a);
  }
  return v;
}

}  // namespace pkm::dynamics
