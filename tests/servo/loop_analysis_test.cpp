// The loop design and analysis against the closed forms of the motion-control textbook (§2.7.3): technical
// optimum speed loop 1/(2T²p² + 2Tp + 1), position loop the 3rd-order Butterworth polynomial with
// ω0 = 1/(2T), their overshoot, settling, margins and ramp error.
#include "servo/loop_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "servo/servo_simulator.hpp"

namespace pkm::servo {
namespace {

ChannelGains technical_optimum(double lag_s, double inertia) {
  ChannelGains g;
  g.lag_s = lag_s;
  g.force_per_command = 1000.0;
  g.command_max = std::numeric_limits<double>::infinity();
  g.error_max = std::numeric_limits<double>::infinity();
  g.inertia = inertia;
  g.speed_gain = inertia / (2.0 * lag_s);
  g.position_gain_per_s = 1.0 / (4.0 * lag_s);
  return g;
}

// The last time |y − 1| > 2 % of a step response y(t), sampled densely up to `horizon`.
double settling_of(const std::function<double(double)>& y, double horizon) {
  double last = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    const double t = horizon * i / 200000.0;
    if (std::abs(y(t) - 1.0) > 0.02) last = t;
  }
  return last;
}

TEST(ServoLoopAnalysis, TechnicalOptimumSpeedLoopIsTheSecondOrderButterworth) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> lag(2e-4, 5e-3), inertia(0.01, 2.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double t_mu = lag(random);
    const ChannelGains g = technical_optimum(t_mu, inertia(random));
    const ChannelAnalysis a = analyse_channel(g, t_mu);
    // ζ = 1/√2, ω_n = 1/(√2 T): y = 1 − e^(−t/2T) (cos(t/2T) + sin(t/2T)), overshoot e^−π.
    EXPECT_NEAR(a.speed_continuous.step.overshoot_pct, 100.0 * std::exp(-std::numbers::pi), 0.05);
    const double settling = settling_of(
        [&](double t) {
          const double x = t / (2.0 * t_mu);
          return 1.0 - std::exp(-x) * (std::cos(x) + std::sin(x));
        },
        40.0 * t_mu);
    EXPECT_NEAR(a.speed_continuous.step.settling_s, settling, 0.01 * settling);
    EXPECT_GT(a.speed_continuous.step.settling_s, 7.0 * t_mu);  // the textbook's "≈ 10 T_μ"
    EXPECT_LT(a.speed_continuous.step.settling_s, 10.5 * t_mu);
    // Open loop 1/(2Tp(Tp + 1)): crossing at ω T = 0.455, phase margin 65.5°, no phase crossover.
    EXPECT_NEAR(a.speed_continuous.margins.phase_margin_deg, 65.53, 0.1);
    EXPECT_TRUE(std::isinf(a.speed_continuous.margins.gain_margin_db));
  }
}

TEST(ServoLoopAnalysis, TechnicalOptimumPositionLoopIsTheThirdOrderButterworth) {
  const double t_mu = 1e-3;
  const ChannelGains g = technical_optimum(t_mu, 0.05);
  const ChannelAnalysis a = analyse_channel(g, t_mu / 4.0);
  EXPECT_NEAR(a.position_continuous.step.overshoot_pct, 8.15, 0.05);
  EXPECT_NEAR(a.position_continuous.step.settling_s / t_mu, 13.3, 0.3);
  EXPECT_NEAR(a.position_continuous.margins.phase_margin_deg, 60.5, 0.2);
  EXPECT_NEAR(a.position_continuous.margins.gain_margin_db, 12.04, 0.05);
  EXPECT_NEAR(a.ramp_error_per_speed_s, 4.0 * t_mu, 1e-12);
  // Sampled at a quarter of T_μ the loops are a little worse than the continuous ones, and still stable.
  EXPECT_GT(a.position_sampled.step.overshoot_pct, a.position_continuous.step.overshoot_pct);
  EXPECT_LT(a.position_sampled.margins.phase_margin_deg, a.position_continuous.margins.phase_margin_deg);
  EXPECT_GT(a.position_sampled.margins.phase_margin_deg, 30.0);
  EXPECT_GT(a.position_sampled.margins.gain_margin_db, 6.0);
}

TEST(ServoLoopAnalysis, ClosedLoopFrequencyResponseIsTheButterworthMagnitude) {
  const double t_mu = 5e-4;
  const ChannelGains g = technical_optimum(t_mu, 0.3);
  for (double f : {10.0, 100.0, 318.0, 1000.0}) {
    const LoopResponse r = loop_response(g, t_mu, f);
    const double w = 2.0 * std::numbers::pi * f;
    // |1/B2(jω)|² = 1/(1 + (ω/ω0)⁴) with ω0 = 1/(√2 T); |1/B3|² = 1/(1 + (ω/ω0)⁶) with ω0 = 1/(2T).
    EXPECT_NEAR(std::norm(r.speed_closed), 1.0 / (1.0 + std::pow(w * std::sqrt(2.0) * t_mu, 4)), 1e-9) << f;
    EXPECT_NEAR(std::norm(r.position_closed), 1.0 / (1.0 + std::pow(w * 2.0 * t_mu, 6)), 1e-9) << f;
    // The sampled loop tends to the continuous one far below the Nyquist frequency.
    if (f <= 10.0) {
      EXPECT_NEAR(std::abs(r.position_closed_sampled), std::abs(r.position_closed), 1e-3);
    }
  }
  // Above the Nyquist frequency of the loop period the sampled response is not defined.
  EXPECT_TRUE(std::isnan(loop_response(g, t_mu, 1.1 / (2.0 * t_mu)).speed_open_sampled.real()));
}

TEST(ServoLoopAnalysis, RampFollowingErrorIsFourTimeConstantsTimesTheSpeed) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> lag(2e-4, 2e-3), speed(5.0, 200.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double t_mu = lag(random), v = speed(random);
    LoopDesign design;
    design.drives = 1;
    design.channels[0] = technical_optimum(t_mu, 0.2);
    const double h = t_mu / 10.0;
    ServoSimulator simulator(design, h);
    simulator.reset(DriveVector::Zero());
    DriveVector reference = DriveVector::Zero(), rate = DriveVector::Zero();
    rate[0] = v;
    const int steps = static_cast<int>(200.0 * t_mu / h);
    for (int k = 0; k < steps; ++k) {
      reference[0] = v * k * h;
      simulator.step(reference, rate);
    }
    const double error = v * steps * h - simulator.position()[0];
    EXPECT_NEAR(error, 4.0 * t_mu * v, 0.01 * 4.0 * t_mu * v) << t_mu << " " << v;
  }
}

TEST(ServoLoopAnalysis, SymmetricOptimumRemovesTheStaticErrorOfALoadAndTheTechnicalOneDoesNot) {
  const double t_mu = 1e-3, inertia = 0.1, load_N = 250.0;
  for (bool symmetric : {false, true}) {
    LoopDesign design;
    design.drives = 1;
    ChannelGains& g = design.channels[0];
    g = technical_optimum(t_mu, inertia);
    if (symmetric) {
      g.speed_integral_s = 4.0 * t_mu;
      g.reference_filter_s = 4.0 * t_mu;
      g.position_gain_per_s = 1.0 / (8.0 * t_mu);
    }
    ServoSimulator simulator(design, t_mu / 4.0);
    simulator.reset(DriveVector::Zero());  // at rest, no load
    DriveVector load = DriveVector::Zero();
    load[0] = load_N;
    simulator.set_load(load);  // a step of load
    const DriveVector zero = DriveVector::Zero();
    for (int k = 0; k < 4000; ++k) simulator.step(zero, zero);
    // P-P cascade: the load is held by a position error d/(k_p K_w); PI speed loop: by the integral.
    const double expected = symmetric ? 0.0 : -load_N / (g.position_gain_per_s * g.speed_gain);
    EXPECT_NEAR(simulator.position()[0], expected, 1e-6 + 1e-4 * std::abs(expected)) << symmetric;
    EXPECT_NEAR(simulator.force()[0], load_N, 1e-6 * load_N);
    const ChannelAnalysis a = analyse_channel(g, t_mu / 4.0);
    EXPECT_GT(a.position_continuous.margins.phase_margin_deg, 30.0);
  }
}

}  // namespace
}  // namespace pkm::servo
