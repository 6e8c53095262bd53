// Rigid inverse dynamics (src/dynamics) against invariants, on random hexapod geometries and every shipped
// mechanism, with random inertial parameters and random smooth trajectories:
//  - power balance: Σ P_j q̇_j = d(T + V_g)/dt − w_ext·t at every instant, T and V_g from their own
//    functions, differentiated in time by a eighth-order stencil;
//  - a Lagrange formulation (mass matrix from the kinetic energy, its derivatives by differences) agrees;
//  - at rest the forces are the static part, and equal src/statics for the platform's weight and a load;
//  - the dynamic part is quadratic in the speed along a path.
#include "dynamics/rigid_dynamics.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <type_traits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "statics/actuator_forces.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

/// A smooth trajectory through home in the controlled coordinates: q(t) = q₀ + A ∘ sin(Ω t + φ).
struct Trajectory {
  const Mechanism* mechanism = nullptr;
  PoseVector centre, amplitude, frequency, phase;

  PoseVector coordinates(double t) const {
    return centre + amplitude.cwiseProduct((frequency * t + phase).array().sin().matrix());
  }
  PoseVector rates(double t) const {
    return amplitude.cwiseProduct(frequency).cwiseProduct((frequency * t + phase).array().cos().matrix());
  }
  Pose pose(double t) const {
    return *mechanism->complete_pose(pose_from_vector(mechanism->convention(), coordinates(t)));
  }
  /// The twist T(q) q̇ of the controlled coordinates' rates.
  Vector6 twist(double t) const {
    TwistBasis basis;
    EXPECT_TRUE(mechanism->controlled_twists(pose(t), basis));
    const AxisMask mask = mechanism->controlled_axes();
    const PoseVector r = rates(t);
    Eigen::VectorXd rate(basis.cols());
    for (int axis = 0, c = 0; axis < 6; ++axis)
      if (mask.controlled[axis]) rate[c++] = r[axis];
    return basis * rate;
  }
};

/// Eighth-order central difference of f at t (evaluated into f's own type: an Eigen expression returned from
/// here would refer to temporaries that are gone). Eighth order lets the step be large enough that rounding
/// stays near 1e-13 while the truncation, (hΩ)⁸, is smaller still: the checks can then ask for 1e-9.
template <class F>
auto derivative(F&& f, double t, double h) {
  using Value = std::decay_t<decltype(f(t))>;
  const Value d = (672.0 * (f(t + h) - f(t - h)) - 168.0 * (f(t + 2 * h) - f(t - 2 * h)) +
                   32.0 * (f(t + 3 * h) - f(t - 3 * h)) - 3.0 * (f(t + 4 * h) - f(t - 4 * h))) /
                  (840.0 * h);
  return d;
}

Trajectory random_trajectory(std::mt19937_64& rng, const Mechanism& mechanism) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Trajectory tr;
  tr.mechanism = &mechanism;
  tr.centre = vector_from_pose(mechanism.convention(), mechanism.home());
  const AxisMask mask = mechanism.controlled_axes();
  for (int axis = 0; axis < 6; ++axis) {
    const bool moves = mask.controlled[axis];
    tr.amplitude[axis] = moves ? (axis < 3 ? 5 + 10 * unit(rng) : 0.02 + 0.03 * unit(rng)) : 0.0;
    tr.frequency[axis] = 2 + 10 * unit(rng);
    tr.phase[axis] = 2 * kPi * unit(rng);
  }
  return tr;
}

dynamics::PlatformMotion motion_at(const Trajectory& tr, double t) {
  dynamics::PlatformMotion m;
  m.pose = tr.pose(t);
  const Vector6 twist = tr.twist(t);
  const Vector6 rate = derivative([&](double s) { return tr.twist(s); }, t, 1e-3);
  m.velocity_mm_s = twist.head<3>();
  m.angular_velocity_rad_s = twist.tail<3>();
  m.acceleration_mm_s2 = rate.head<3>();
  m.angular_acceleration_rad_s2 = rate.tail<3>();
  return m;
}

struct Case {
  std::string label;
  Machine machine;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  std::mt19937_64 rng(2026);
  for (int i = 0; i < 5; ++i)
    out.push_back({fmt::format("random hexapod {}", i), test::random_hexapod_machine(rng, i)});
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml", "tripod.yaml",
        "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    out.push_back({file, test::machine_from_example(std::string("examples/machines/") + file)});
  }
  return out;
}

TEST(RigidDynamics, DrivePowerIsTheRateOfKineticAndPotentialEnergyPlusTheLoad) {
  std::mt19937_64 rng(7);
  for (const Case& c : cases()) {
    const Mechanism& mech = *c.machine.mechanism;
    for (int trial = 0; trial < 3; ++trial) {
      SCOPED_TRACE(fmt::format("{} trial {}", c.label, trial));
      const DynamicsParameters p = test::random_dynamics_parameters(rng, mech.actuator_count());
      const Trajectory tr = random_trajectory(rng, mech);
      statics::Wrench load{Eigen::Vector3d(200, -100, 300), Eigen::Vector3d(1e4, -5e3, 2e3)};
      if (mech.is_planar()) load = {Eigen::Vector3d(200, -100, 0), Eigen::Vector3d(0, 0, 2e3)};
      for (double t : {0.05, 0.21, 0.37}) {
        const dynamics::PlatformMotion m = motion_at(tr, t);
        auto forces = dynamics::inverse_dynamics(mech, p, m, load);
        ASSERT_TRUE(forces.ok()) << forces.error().message;
        const double drive_power_W = forces->total.dot(forces->actuator_rates) * 1e-3;
        auto energy = [&](double s) {
          const dynamics::PlatformMotion ms = motion_at(tr, s);
          return *dynamics::kinetic_energy_J(mech, p, ms) + *dynamics::gravity_potential_J(mech, p, ms.pose);
        };
        const double energy_rate_W = derivative(energy, t, 1e-3);
        Vector6 twist;
        twist << m.velocity_mm_s, m.angular_velocity_rad_s;
        const double load_power_W =
            (load.force_N.dot(twist.head<3>()) + load.moment_Nmm.dot(twist.tail<3>())) * 1e-3;
        const double scale = std::abs(drive_power_W) + std::abs(energy_rate_W) + std::abs(load_power_W);
        EXPECT_NEAR(drive_power_W, energy_rate_W - load_power_W, 1e-8 * scale)
            << "drive " << drive_power_W << " W, energy rate " << energy_rate_W << " W, load "
            << load_power_W;
      }
    }
  }
}

TEST(RigidDynamics, AtRestTheForcesAreStaticAndMatchStatics) {
  std::mt19937_64 rng(11);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    DynamicsParameters p = test::random_dynamics_parameters(rng, mech.actuator_count());
    // statics carries the platform's weight; struts massless here, so both models are the same bodies.
    for (int j = 0; j < p.strut_count; ++j) p.struts[j] = StrutDynamics{};
    p.payload = BodyInertia{};
    const Trajectory tr = random_trajectory(rng, mech);
    dynamics::PlatformMotion m;
    m.pose = tr.pose(0.13);
    statics::Wrench load{Eigen::Vector3d(100, 50, -300), Eigen::Vector3d(2e3, 1e3, -4e3)};
    if (mech.is_planar()) load = {Eigen::Vector3d(100, 50, 0), Eigen::Vector3d(0, 0, -4e3)};
    auto forces = dynamics::inverse_dynamics(mech, p, m, load);
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    EXPECT_LE(forces->dynamic_part.cwiseAbs().maxCoeff(), 1e-12 * forces->total.cwiseAbs().maxCoeff());
    // The same load plus the platform's weight at its centre of mass, through statics.
    const Eigen::Vector3d weight_N = p.platform.mass_kg * p.gravity_mm_s2 * 1e-3;
    const Eigen::Vector3d arm = m.pose.rotation * p.platform.com_mm;
    const statics::Wrench total{load.force_N + weight_N, load.moment_Nmm + arm.cross(weight_N)};
    auto expected = statics::actuator_forces(mech, m.pose, total);
    ASSERT_TRUE(expected.ok()) << expected.error().message;
    EXPECT_LE((forces->total - *expected).cwiseAbs().maxCoeff(), 1e-9 * expected->cwiseAbs().maxCoeff())
        << "dynamics " << forces->total.transpose() << "\nstatics  " << expected->transpose();
  }
}

TEST(RigidDynamics, TheDynamicPartScalesWithTheSquareOfTheSpeedAlongAPath) {
  std::mt19937_64 rng(13);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    const DynamicsParameters p = test::random_dynamics_parameters(rng, mech.actuator_count());
    const Trajectory tr = random_trajectory(rng, mech);
    const dynamics::PlatformMotion m = motion_at(tr, 0.29);
    dynamics::PlatformMotion faster = m;
    // The same path at λ times the speed: twist × λ, its rate × λ² (at constant path speed).
    const double lambda = 3.0;
    faster.velocity_mm_s *= lambda;
    faster.angular_velocity_rad_s *= lambda;
    faster.acceleration_mm_s2 *= lambda * lambda;
    faster.angular_acceleration_rad_s2 *= lambda * lambda;
    auto slow = dynamics::inverse_dynamics(mech, p, m);
    auto fast = dynamics::inverse_dynamics(mech, p, faster);
    ASSERT_TRUE(slow.ok() && fast.ok());
    EXPECT_LE((fast->dynamic_part - lambda * lambda * slow->dynamic_part).cwiseAbs().maxCoeff(),
              1e-10 * fast->dynamic_part.cwiseAbs().maxCoeff());
    EXPECT_LE((fast->static_part - slow->static_part).cwiseAbs().maxCoeff(),
              1e-12 * slow->static_part.cwiseAbs().maxCoeff());
  }
}

// Lagrange's equations in the controlled coordinates q, built independently of the virtual-power solve: the
// mass matrix from the kinetic energy alone (T(q, q̇) = ½ q̇ᵀ M q̇, polarised), its time and coordinate
// derivatives and the potential's gradient by eighth-order differences, the drive forces through the
// coordinate Jacobian (Mechanism::jacobian): J_qᵀ P = M q̈ + Ṁ q̇ − ½ ∂_q(q̇ᵀ M q̇) + ∂_q V.
TEST(RigidDynamics, AgreesWithLagrangesEquations) {
  std::mt19937_64 rng(19);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    const DynamicsParameters p = test::random_dynamics_parameters(rng, mech.actuator_count());
    const Trajectory tr = random_trajectory(rng, mech);
    const AxisMask mask = mech.controlled_axes();
    std::vector<int> axes;
    for (int axis = 0; axis < 6; ++axis)
      if (mask.controlled[axis]) axes.push_back(axis);
    const int n = static_cast<int>(axes.size());
    auto pose_at = [&](const PoseVector& q) {
      return *mech.complete_pose(pose_from_vector(mech.convention(), q));
    };
    auto energy_of_rates = [&](const PoseVector& q, const Eigen::VectorXd& rates) {
      dynamics::PlatformMotion m;
      m.pose = pose_at(q);
      TwistBasis basis;
      EXPECT_TRUE(mech.controlled_twists(m.pose, basis));
      const Vector6 twist = basis * rates;
      m.velocity_mm_s = twist.head<3>();
      m.angular_velocity_rad_s = twist.tail<3>();
      return *dynamics::kinetic_energy_J(mech, p, m);
    };
    auto mass_matrix = [&](const PoseVector& q) {
      Eigen::MatrixXd mass(n, n);
      for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
          Eigen::VectorXd plus = Eigen::VectorXd::Zero(n), minus = Eigen::VectorXd::Zero(n);
          plus[i] += 1.0, plus[k] += 1.0;
          minus[i] += 1.0, minus[k] -= 1.0;
          mass(i, k) = 0.5 * (energy_of_rates(q, plus) - energy_of_rates(q, minus));
        }
      }
      return mass;
    };
    const double t = 0.17;
    const PoseVector q = tr.coordinates(t);
    Eigen::VectorXd rate(n), accel(n);
    const PoseVector all_rates = tr.rates(t);
    const PoseVector all_accels = derivative([&](double s) { return tr.rates(s); }, t, 1e-3);
    for (int i = 0; i < n; ++i) rate[i] = all_rates[axes[i]], accel[i] = all_accels[axes[i]];
    const Eigen::MatrixXd mass = mass_matrix(q);
    const Eigen::MatrixXd mass_rate =
        derivative([&](double s) { return mass_matrix(tr.coordinates(s)); }, t, 1e-3);
    Eigen::VectorXd lagrange = mass * accel + mass_rate * rate;
    for (int i = 0; i < n; ++i) {
      const double h = axes[i] < 3 ? 0.5 : 1e-3;
      auto along = [&](double step) {
        PoseVector moved = q;
        moved[axes[i]] += step;
        return rate.dot(mass_matrix(moved) * rate);
      };
      auto potential = [&](double step) {
        PoseVector moved = q;
        moved[axes[i]] += step;
        return *dynamics::gravity_potential_J(mech, p, pose_at(moved));
      };
      lagrange[i] += -0.5 * derivative(along, 0.0, h) + derivative(potential, 0.0, h);
    }
    lagrange *= 1e3;  // J per mm (or rad) → N (or N·mm)
    auto forces = dynamics::inverse_dynamics(mech, p, motion_at(tr, t));
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    auto jacobian = mech.jacobian(tr.pose(t));
    ASSERT_TRUE(jacobian.ok());
    const Eigen::VectorXd virtual_power = jacobian->transpose() * forces->total;
    EXPECT_LE((virtual_power - lagrange).cwiseAbs().maxCoeff(), 1e-9 * lagrange.cwiseAbs().maxCoeff())
        << "Newton–Euler " << virtual_power.transpose() << "\nLagrange     " << lagrange.transpose();
  }
}

}  // namespace
}  // namespace pkm
