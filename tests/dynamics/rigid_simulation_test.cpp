// Forward dynamics of the rigid machine under drive forces (src/dynamics/rigid_simulation.hpp), on the ch5
// hexapod, the planar biped, the hexaglide (carriages) and five random hexapods with random inertial
// parameters:
//  - the inverse dynamics' forces, commanded along a smooth motion, give that motion back (forward and
//    inverse dynamics are each other's inverse);
//  - through the drive models of Smirnov 2019, §4.2: a speed-dependent drive (static characteristic) and a
//    lagging one reproduce the motion when the command is pre-compensated by the model's inverse; left
//    uncompensated, the lag's open-loop error grows with τ (and vanishes with it);
//  - free motion without gravity keeps its kinetic energy; the static forces hold the platform at rest.
#include "dynamics/rigid_simulation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/rigid_dynamics.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateVector;

struct RigidCase {
  std::string label;
  Machine machine;
  DynamicsParameters parameters;
};

std::vector<RigidCase> rigid_simulation_cases() {
  std::vector<RigidCase> cases;
  std::mt19937_64 rng(4242);
  for (const char* file : {"hexapod_ch5.yaml", "planar2.yaml"}) {
    RigidCase c{file, test::machine_from_example(std::string("examples/machines/") + file), {}};
    c.parameters = c.machine.dynamics;
    cases.push_back(std::move(c));
  }
  {
    RigidCase c{"hexaglide.yaml", test::machine_from_example("examples/machines/hexaglide.yaml"), {}};
    c.parameters = test::random_dynamics_parameters(rng, c.machine.mechanism->actuator_count());
    cases.push_back(std::move(c));
  }
  // Five random hexapods, or PKM_RANDOM_GEOMETRIES (the sanitizer run takes one: its simulations are 20×
  // slower, and the shipped machines stay in every run).
  for (int i = 0; i < test::random_geometry_count(); ++i) {
    RigidCase c{fmt::format("random hexapod {}", i), test::random_hexapod_machine(rng, i), {}};
    c.parameters = test::random_dynamics_parameters(rng, 6, false);
    cases.push_back(std::move(c));
  }
  return cases;
}

/// A smooth motion from home within the basis' span: the tool point swings along one direction and drifts
/// along another, the platform turns about a fixed axis (so the angular velocity and acceleration are exact).
struct SmoothMotion {
  Pose home;
  Eigen::Vector3d swing = Eigen::Vector3d::Zero(), drift = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double turn_rad = 0.0;
  double omega_rad_s = 2 * kPi * 1.5;

  dynamics::PlatformMotion at(double t) const {
    dynamics::PlatformMotion m;
    const double w = omega_rad_s, s = std::sin(w * t), c = std::cos(w * t);
    m.pose.position_mm = home.position_mm + swing * s + drift * (1 - c);
    m.velocity_mm_s = swing * w * c + drift * w * s;
    m.acceleration_mm_s2 = -swing * w * w * s + drift * w * w * c;
    const double angle = turn_rad * (1 - c), rate = turn_rad * w * s, accel = turn_rad * w * w * c;
    m.pose.rotation = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * home.rotation;
    m.angular_velocity_rad_s = rate * axis;
    m.angular_acceleration_rad_s2 = accel * axis;
    return m;
  }
};

SmoothMotion random_smooth_motion(std::mt19937_64& rng, const dynamics::FreePlatformModel& model) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  SmoothMotion motion;
  motion.home = *model.mechanism->complete_pose(model.mechanism->home());
  Eigen::Vector3d linear_a = Eigen::Vector3d::Zero(), linear_b = Eigen::Vector3d::Zero(),
                  angular = Eigen::Vector3d::Zero();
  for (int k = 0; k < model.coordinates; ++k) {
    const auto column = model.basis.col(k);
    if (column.tail<3>().squaredNorm() == 0.0) {
      linear_a += unit(rng) * column.head<3>();
      linear_b += unit(rng) * column.head<3>();
    } else {
      angular += unit(rng) * column.tail<3>();
    }
  }
  motion.swing = 15.0 * linear_a.normalized();
  motion.drift = 5.0 * linear_b.normalized();
  if (angular.norm() > 0.0) {
    motion.axis = angular.normalized();
    motion.turn_rad = 0.03;
  }
  return motion;
}

CoordinateVector basis_rates(const dynamics::FreePlatformModel& model, const dynamics::PlatformMotion& m) {
  dynamics::Twist twist;
  twist << m.velocity_mm_s, m.angular_velocity_rad_s;
  return model.basis.transpose() * twist;  // the basis' columns are orthonormal unit twists
}

/// The inverse dynamics' forces along the motion, passed through the inverse of the drive model
/// (compensate) or commanded as they are.
class InverseDynamicsCommand final : public dynamics::DriveCommand {
 public:
  InverseDynamicsCommand(const RigidCase& c, const SmoothMotion& motion, bool compensate)
      : case_(c), motion_(motion), compensate_(compensate) {}
  void command_N(double t, ActuatorVector& out) const override {
    const dynamics::DriveForces forces = force_at(t);
    if (!compensate_) {
      out = forces.total;
      return;
    }
    const double h = 1e-5;
    const ActuatorVector rate = (force_at(t + h).total - force_at(t - h).total) / (2 * h);
    out = dynamics::command_for_force(case_.parameters, forces.total, forces.actuator_rates, rate);
  }
  dynamics::DriveForces force_at(double t) const {
    auto forces = dynamics::inverse_dynamics(*case_.machine.mechanism, case_.parameters, motion_.at(t));
    EXPECT_TRUE(forces.ok()) << forces.error().message;
    return *forces;
  }

 private:
  const RigidCase& case_;
  const SmoothMotion& motion_;
  bool compensate_;
};

struct TrackingError {
  double position_mm = 0.0;
  double rotation_rad = 0.0;
};

/// Simulates `duration_s` of the motion under the inverse dynamics' command and returns the largest
/// deviation.
TrackingError simulate_tracking(const RigidCase& c, const dynamics::FreePlatformModel& model,
                                const SmoothMotion& motion, bool compensate, double duration_s = 1.0) {
  dynamics::PlatformIntegration integration;
  integration.abs_tolerance_mm = 1e-9;
  integration.rel_tolerance = 1e-11;
  dynamics::RigidSimulator simulator(model, integration);
  const InverseDynamicsCommand command(c, motion, compensate);
  const dynamics::PlatformMotion start = motion.at(0.0);
  const ActuatorVector initial_force = command.force_at(0.0).total;
  EXPECT_TRUE(simulator.start(0.0, start.pose, basis_rates(model, start), initial_force).ok());
  TrackingError worst;
  for (int k = 1; k <= 100; ++k) {
    const double t = duration_s * k / 100;
    const Status advanced = simulator.advance_to(t, command);
    EXPECT_TRUE(advanced.ok()) << c.label << ": " << advanced.error().message;
    if (!advanced) break;
    const Pose expected = motion.at(t).pose, actual = simulator.pose();
    worst.position_mm = std::max(worst.position_mm, (actual.position_mm - expected.position_mm).norm());
    worst.rotation_rad = std::max(worst.rotation_rad,
                                  Eigen::AngleAxisd(actual.rotation * expected.rotation.transpose()).angle());
  }
  return worst;
}

dynamics::FreePlatformModel free_model_of(const RigidCase& c) {
  dynamics::FreePlatformModel model;
  const Status made = dynamics::make_free_platform_model(*c.machine.mechanism, c.parameters, "",
                                                         "the rigid simulation", model);
  EXPECT_TRUE(made.ok()) << c.label << ": " << made.error().message;
  return model;
}

TEST(RigidSimulation, TheInverseDynamicsForcesGiveTheMotionBack) {
  std::mt19937_64 rng(77);
  for (const RigidCase& c : rigid_simulation_cases()) {
    const dynamics::FreePlatformModel model = free_model_of(c);
    const SmoothMotion motion = random_smooth_motion(rng, model);
    const TrackingError error = simulate_tracking(c, model, motion, false);
    // 15 mm swings at 1.5 Hz (up to 1.3 m/s²): what is left is the integrator's, open loop over a second.
    EXPECT_LT(error.position_mm, 1e-5) << c.label;
    EXPECT_LT(error.rotation_rad, 1e-7) << c.label;
  }
}

TEST(RigidSimulation, DriveModelsReproduceTheMotionWhenTheCommandIsCompensated) {
  std::mt19937_64 rng(78);
  for (const DriveModel drive : {DriveModel::static_characteristic, DriveModel::first_order_lag}) {
    for (RigidCase& c : rigid_simulation_cases()) {
      c.parameters.drive = drive;
      c.parameters.drive_speed_gain_N_s_mm = 5.0;  // 5 N per mm/s: 0.5 kN at 100 mm/s
      c.parameters.drive_lag_s = 0.002;
      const dynamics::FreePlatformModel model = free_model_of(c);
      const SmoothMotion motion = random_smooth_motion(rng, model);
      const TrackingError compensated = simulate_tracking(c, model, motion, true);
      const TrackingError raw = simulate_tracking(c, model, motion, false);
      EXPECT_LT(compensated.position_mm, 1e-4) << c.label;
      // The uncompensated drive gives a different force: the open-loop motion drifts by far more.
      EXPECT_GT(raw.position_mm, 1e3 * std::max(compensated.position_mm, 1e-7)) << c.label;
    }
  }
}

TEST(RigidSimulation, TheUncompensatedLagsErrorShrinksWithItsTimeConstant) {
  std::mt19937_64 rng(79);
  std::vector<RigidCase> cases = rigid_simulation_cases();
  RigidCase& c = cases.front();  // the ch5 hexapod
  c.parameters.drive = DriveModel::first_order_lag;
  const dynamics::FreePlatformModel model = free_model_of(c);
  const SmoothMotion motion = random_smooth_motion(rng, model);
  std::vector<double> errors;
  for (const double tau : {1e-3, 0.5e-3, 0.25e-3}) {
    c.parameters.drive_lag_s = tau;
    errors.push_back(simulate_tracking(c, model, motion, false, 0.2).position_mm);
  }
  // P lags u by ≈ τ: the force error, and so the drift, is first order in τ (over 0.2 s, where the drift
  // is still small: 0.23 mm at 1 ms; open loop it grows as t², to 3.5 mm in a second).
  EXPECT_GT(errors[2], 1e-3);
  EXPECT_NEAR(errors[0] / errors[1], 2.0, 0.1);
  EXPECT_NEAR(errors[1] / errors[2], 2.0, 0.1);
}

TEST(RigidSimulation, FreeMotionWithoutGravityKeepsItsKineticEnergy) {
  std::mt19937_64 rng(80);
  for (RigidCase& c : rigid_simulation_cases()) {
    c.parameters.gravity_mm_s2.setZero();
    const dynamics::FreePlatformModel model = free_model_of(c);
    const SmoothMotion motion = random_smooth_motion(rng, model);
    const dynamics::PlatformMotion start = motion.at(0.25 / 1.5);  // moving: a quarter period in
    dynamics::PlatformIntegration integration;
    integration.abs_tolerance_mm = 1e-10;
    integration.rel_tolerance = 1e-12;
    dynamics::RigidSimulator simulator(model, integration);
    ASSERT_TRUE(
        simulator.start(0.0, start.pose, basis_rates(model, start), ActuatorVector::Zero(model.struts)).ok());
    const dynamics::SampledDriveCommand no_force({0.0}, {ActuatorVector::Zero(model.struts)});
    auto kinetic = [&](const Pose& pose, const CoordinateVector& rates) {
      dynamics::PlatformMotion m;
      m.pose = pose;
      const dynamics::Twist twist = model.basis * rates;
      m.velocity_mm_s = twist.head<3>();
      m.angular_velocity_rad_s = twist.tail<3>();
      return *dynamics::kinetic_energy_J(*c.machine.mechanism, c.parameters, m);
    };
    const double initial = kinetic(start.pose, basis_rates(model, start));
    ASSERT_GT(initial, 0.0);
    double worst = 0.0, travelled = 0.0;
    for (int k = 1; k <= 20; ++k) {
      const Status advanced = simulator.advance_to(0.005 * k, no_force);
      ASSERT_TRUE(advanced.ok()) << c.label << ": " << advanced.error().message;
      worst = std::max(worst, std::abs(kinetic(simulator.pose(), simulator.rates()) / initial - 1.0));
      travelled = (simulator.pose().position_mm - start.pose.position_mm).norm();
    }
    EXPECT_LT(worst, 1e-8) << c.label;
    EXPECT_GT(travelled, 0.5) << c.label;  // it moved: the energy was carried through a real motion
  }
}

TEST(RigidSimulation, TheStaticForcesHoldThePlatformAtRest) {
  for (const RigidCase& c : rigid_simulation_cases()) {
    const dynamics::FreePlatformModel model = free_model_of(c);
    dynamics::PlatformMotion rest;
    rest.pose = *c.machine.mechanism->complete_pose(c.machine.mechanism->home());
    auto forces = dynamics::inverse_dynamics(*c.machine.mechanism, c.parameters, rest);
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    dynamics::RigidSimulator simulator(model);
    ASSERT_TRUE(
        simulator.start(0.0, rest.pose, CoordinateVector::Zero(model.coordinates), forces->total).ok());
    const dynamics::SampledDriveCommand hold({0.0}, {forces->total});
    ASSERT_TRUE(simulator.advance_to(1.0, hold).ok());
    EXPECT_LT((simulator.pose().position_mm - rest.pose.position_mm).norm(), 1e-6) << c.label;
    // Without them it falls: g·t²/2 ≈ 4.9 m in a second, well out of reach.
    dynamics::RigidSimulator falling(model);
    ASSERT_TRUE(falling.start(0.0, rest.pose, CoordinateVector::Zero(model.coordinates), forces->total).ok());
    const dynamics::SampledDriveCommand none({0.0}, {ActuatorVector::Zero(model.struts)});
    ASSERT_TRUE(falling.advance_to(0.01, none).ok());
    EXPECT_GT((falling.pose().position_mm - rest.pose.position_mm).norm(), 0.1) << c.label;
  }
}

TEST(RigidSimulation, SampledCommandsInterpolateLinearlyAndHoldBeyondTheEnds) {
  ActuatorVector a(2), b(2), out;
  a << 0.0, 10.0;
  b << 4.0, 30.0;
  const dynamics::SampledDriveCommand command({1.0, 2.0}, {a, b});
  command.command_N(1.25, out);
  EXPECT_DOUBLE_EQ(out[0], 1.0);
  EXPECT_DOUBLE_EQ(out[1], 15.0);
  command.command_N(0.0, out);
  EXPECT_DOUBLE_EQ(out[1], 10.0);
  command.command_N(5.0, out);
  EXPECT_DOUBLE_EQ(out[0], 4.0);
}

TEST(RigidSimulation, AMachineWithoutAFreePlatformIsRefusedByName) {
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  dynamics::FreePlatformModel model;
  const Status made = dynamics::make_free_platform_model(*tripod.mechanism, tripod.dynamics, "",
                                                         "the rigid simulation", model);
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("the rigid simulation needs one"), std::string::npos)
      << made.error().message;
}

}  // namespace
}  // namespace pkm
