// The servo simulator's plant step against a numerical integration of the same equations (a lag per drive,
// A ẇ = F − d, the command held over the step), on random coupled plants, gains, loads and set points; and
// the limits of Fig. 2.31.
#include "servo/servo_simulator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <random>

namespace pkm::servo {
namespace {

constexpr int kSimDrives = 3;

LoopDesign random_design(std::mt19937& random) {
  std::uniform_real_distribution<double> lag(3e-4, 3e-3), inertia(0.02, 1.0), unit(0.5, 1.5);
  LoopDesign design;
  design.drives = kSimDrives;
  for (int j = 0; j < kSimDrives; ++j) {
    ChannelGains& g = design.channels[j];
    g.lag_s = lag(random);
    g.inertia = inertia(random);
    g.force_per_command = 1000.0 * unit(random);
    g.command_max = std::numeric_limits<double>::infinity();
    g.error_max = std::numeric_limits<double>::infinity();
    g.speed_gain = unit(random) * g.inertia / (2.0 * g.lag_s);
    g.position_gain_per_s = unit(random) / (4.0 * g.lag_s);
    g.speed_integral_s = j == 1 ? 4.0 * g.lag_s : 0.0;
    g.reference_filter_s = j == 1 ? 4.0 * g.lag_s : 0.0;
    g.velocity_feedforward = 0.5;
  }
  return design;
}

// A random symmetric positive definite inertia matrix around the design's diagonal.
DriveMatrix random_inertia(std::mt19937& random, const LoopDesign& design) {
  std::uniform_real_distribution<double> coupling(-0.3, 0.3);
  DriveMatrix a = DriveMatrix::Zero();
  for (int i = 0; i < kSimDrives; ++i) {
    a(i, i) = design.channels[i].inertia;
    for (int k = 0; k < i; ++k) {
      a(i, k) = a(k, i) =
          coupling(random) * std::sqrt(design.channels[i].inertia * design.channels[k].inertia);
    }
  }
  return a;
}

TEST(ServoSimulator, EachStepIsTheExactSolutionOfTheHeldCommandsPlant) {
  std::mt19937 random(1717);
  std::uniform_real_distribution<double> load(-200.0, 200.0), position(-5.0, 5.0);
  for (int trial = 0; trial < 5; ++trial) {
    const LoopDesign design = random_design(random);
    const DriveMatrix a = random_inertia(random, design);
    DriveMatrix inverse = DriveMatrix::Zero();
    inverse.topLeftCorner(kSimDrives, kSimDrives) = a.topLeftCorner(kSimDrives, kSimDrives).inverse();
    const double h = 2.5e-4;
    ServoSimulator simulator(design, h);
    simulator.set_inverse_inertia(inverse);
    DriveVector d = DriveVector::Zero(), start = DriveVector::Zero();
    for (int j = 0; j < kSimDrives; ++j) {
      d[j] = load(random);
      start[j] = position(random);
    }
    simulator.set_load(d);
    simulator.reset(start);
    DriveVector reference = start, rate = DriveVector::Zero();
    for (int k = 0; k < 40; ++k) {
      for (int j = 0; j < kSimDrives; ++j) rate[j] = 30.0 * std::sin(0.3 * k + j);
      reference += rate * h;
      const ServoSimulator::StateVector before = simulator.state();
      simulator.step(reference, rate);
      DriveVector force_command = DriveVector::Zero();
      for (int j = 0; j < kSimDrives; ++j)
        force_command[j] = simulator.command()[j] * design.channels[j].force_per_command;
      // x = (q, w, F) per drive: q̇ = w, A ẇ = F − d, T_μ Ḟ = F_cmd − F.
      using State = std::array<double, 3 * kSimDrives>;
      State x{};
      for (int j = 0; j < kSimDrives; ++j) {
        x[j] = before[j];
        x[kSimDrives + j] = before[kMaxActuators + j];
        x[2 * kSimDrives + j] = before[2 * kMaxActuators + j];
      }
      auto system = [&](const State& s, State& ds, double) {
        Eigen::Vector3d net;
        for (int j = 0; j < kSimDrives; ++j) {
          ds[j] = s[kSimDrives + j];
          net[j] = s[2 * kSimDrives + j] - d[j];
          ds[2 * kSimDrives + j] = (force_command[j] - s[2 * kSimDrives + j]) / design.channels[j].lag_s;
        }
        const Eigen::Vector3d acceleration = inverse.topLeftCorner<3, 3>() * net;
        for (int j = 0; j < kSimDrives; ++j) ds[kSimDrives + j] = acceleration[j];
      };
      namespace odeint = boost::numeric::odeint;
      odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_dopri5<State>>(1e-13, 1e-13),
                                 system, x, 0.0, h, h / 50.0);
      for (int j = 0; j < kSimDrives; ++j) {
        EXPECT_NEAR(simulator.position()[j], x[j], 1e-9 * (1.0 + std::abs(x[j]))) << trial << " " << k;
        EXPECT_NEAR(simulator.speed()[j], x[kSimDrives + j], 1e-8 * (1.0 + std::abs(x[kSimDrives + j])));
        EXPECT_NEAR(simulator.force()[j], x[2 * kSimDrives + j],
                    1e-8 * (1.0 + std::abs(x[2 * kSimDrives + j])));
      }
    }
  }
}

TEST(ServoSimulator, LimitsActAndAreFlaggedPerDrive) {
  std::mt19937 random(5);
  LoopDesign design = random_design(random);
  design.channels[0].error_max = 0.5;
  design.channels[2].command_max = 0.2 * design.channels[2].force_per_command;
  ServoSimulator simulator(design, 2.5e-4);
  simulator.reset(DriveVector::Zero());
  DriveVector reference = DriveVector::Zero();
  reference.head(kSimDrives).setConstant(3.0);  // a step far beyond e_max
  simulator.step(reference, DriveVector::Zero());
  EXPECT_EQ(simulator.clamps().error, 1u);  // drive 0 only
  EXPECT_EQ(simulator.clamps().command & 4u, 4u);
  EXPECT_NEAR(std::abs(simulator.command()[2]), 0.2, 1e-12);
  // With the limits the response is slower but reaches the set point without winding up.
  for (int k = 0; k < 40000; ++k) simulator.step(reference, DriveVector::Zero());
  for (int j = 0; j < kSimDrives; ++j) EXPECT_NEAR(simulator.position()[j], 3.0, 1e-6) << j;
  EXPECT_EQ(simulator.clamps().error | simulator.clamps().command, 0u);
}

}  // namespace
}  // namespace pkm::servo
