// The drives' imperfections in the servo simulator (docs/servo.md, "Drive imperfections"), each by the
// signature it leaves: Coulomb friction a dead zone where P loops stop short and a glitch in the following
// error where a drive reverses (growing with the friction); backlash a lost motion of exactly its width at
// every reversal; the encoder's counts a noise floor in the error that grows with the count; a sampling delay
// a step's overshoot growing with it, and past some delay an unstable loop; the static characteristic its
// dead zone and its saturation. Without any, the simulator is the
// same bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "servo/servo_simulator.hpp"

namespace pkm::servo {
namespace {

constexpr double kLoopS = 2.5e-4;  // the drives' loop period

// One drive tuned to the technical optimum for the inertia it moves (loop_design.cpp's gains).
LoopDesign one_drive(double lag_s = 1e-3, double inertia = 0.5) {
  LoopDesign design;
  design.drives = 1;
  ChannelGains& g = design.channels[0];
  g.lag_s = lag_s;
  g.inertia = inertia;
  g.force_per_command = 3000.0;
  g.command_max = std::numeric_limits<double>::infinity();
  g.error_max = std::numeric_limits<double>::infinity();
  g.speed_gain = inertia / (2.0 * lag_s);
  g.position_gain_per_s = 1.0 / (4.0 * lag_s);
  return design;
}

// A smooth move from 0 to `target` in 0.1 s (a cubic with zero speed at both ends), then rest.
struct SmoothMove {
  double target = 0.0;
  double position(double t) const {
    const double u = std::min(1.0, t / 0.1);
    return target * u * u * (3.0 - 2.0 * u);
  }
  double speed(double t) const {
    const double u = std::min(1.0, t / 0.1);
    return target * 6.0 * u * (1.0 - u) / 0.1;
  }
};

struct Trace {
  std::vector<double> reference, motor, actuator, speed;
};

// The drive following `reference(t)` (and its speed) for `duration_s`, from rest at reference(0).
template <typename Reference, typename Speed>
Trace follow(const LoopDesign& design, Reference reference, Speed speed, double duration_s) {
  ServoSimulator simulator(design, kLoopS);
  DriveVector start = DriveVector::Zero();
  start[0] = reference(0.0);
  simulator.reset(start);
  Trace trace;
  const long steps = std::lround(duration_s / kLoopS);
  DriveVector r = DriveVector::Zero(), v = DriveVector::Zero();
  for (long k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) * kLoopS;
    r[0] = reference(t);
    v[0] = speed(t);
    simulator.step(r, v);
    trace.reference.push_back(r[0]);
    trace.motor.push_back(simulator.position()[0]);
    trace.actuator.push_back(simulator.actuator_position()[0]);
    trace.speed.push_back(simulator.speed()[0]);
  }
  return trace;
}

Trace follow_sine(const LoopDesign& design, double amplitude, double frequency_hz, double duration_s) {
  const double w = 2.0 * std::numbers::pi * frequency_hz;
  return follow(
      design, [&](double t) { return amplitude * std::sin(w * t); },
      [&](double t) { return amplitude * w * std::cos(w * t); }, duration_s);
}

double max_abs_error(const Trace& trace, std::size_t from, std::size_t to) {
  double worst = 0.0;
  for (std::size_t k = from; k < std::min(to, trace.reference.size()); ++k)
    worst = std::max(worst, std::abs(trace.reference[k] - trace.actuator[k]));
  return worst;
}

TEST(ServoImperfections, NoneGivenIsTheIdealSimulatorBitForBit) {
  LoopDesign ideal = one_drive();
  LoopDesign zeros = ideal;
  zeros.channels[0].friction_coulomb = zeros.channels[0].friction_static = 0.0;
  zeros.channels[0].backlash = zeros.channels[0].encoder_resolution = 0.0;
  const Trace a = follow_sine(ideal, 5.0, 2.0, 0.6);
  const Trace b = follow_sine(zeros, 5.0, 2.0, 0.6);
  EXPECT_EQ(a.motor, b.motor);
  EXPECT_EQ(a.actuator, a.motor);
}

// P loops (technical optimum) hold a drive at rest only by a position error: under Coulomb friction the
// drive stops wherever the force K_w·k_p·e falls within the static friction, short of the set point.
TEST(ServoImperfections, CoulombFrictionLeavesADeadZoneThatPLoopsStopIn) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> friction(20.0, 200.0), move(-3.0, 3.0);
  for (int trial = 0; trial < 6; ++trial) {
    LoopDesign design = one_drive();
    ChannelGains& g = design.channels[0];
    g.friction_coulomb = g.friction_static = friction(random);
    const double target = move(random);
    const SmoothMove move_to{target};
    auto reference = [&](double t) { return move_to.position(t); };
    auto speed = [&](double t) { return move_to.speed(t); };
    const Trace trace = follow(design, reference, speed, 0.5);
    const double dead_zone = g.friction_static / (g.speed_gain * g.position_gain_per_s);
    const double rest_error = std::abs(target - trace.actuator.back());
    EXPECT_LE(rest_error, dead_zone * (1.0 + 1e-9)) << "friction " << g.friction_coulomb;
    EXPECT_GT(rest_error, 0.02 * dead_zone) << "friction " << g.friction_coulomb;  // it did stop short
    EXPECT_EQ(trace.speed.back(), 0.0);                                            // stuck, not creeping
    // The same move without friction ends on the set point.
    LoopDesign ideal = one_drive();
    EXPECT_LT(std::abs(target - follow(ideal, reference, speed, 0.5).actuator.back()), 1e-9);
  }
}

// On a sine the drive reverses at the peaks: friction holds it there until the loop's force overcomes it, a
// spike in the following error right after the reversal (the quadrant glitch of a circle test), growing
// with the friction. The set point's speed is fed forward, so that the loops' own lag does not hide it.
TEST(ServoImperfections, FrictionMakesAGlitchWhereTheDriveReverses) {
  const double amplitude = 5.0, frequency = 1.0;
  const std::size_t period_steps = static_cast<std::size_t>(std::lround(1.0 / frequency / kLoopS));
  const std::size_t quarter = period_steps / 4;
  // The symmetric optimum: its speed integral takes up a steady friction along the stroke, so what friction
  // leaves is the glitch where the drive reverses and the integral has to turn round.
  auto tuned = [](double friction) {
    LoopDesign design = one_drive();
    ChannelGains& g = design.channels[0];
    g.speed_integral_s = g.reference_filter_s = 4.0 * g.lag_s;
    g.position_gain_per_s = 1.0 / (8.0 * g.lag_s);
    g.friction_coulomb = g.friction_static = friction;
    return design;
  };
  const Trace ideal = follow_sine(tuned(0.0), amplitude, frequency, 2.0);
  double previous_glitch = 0.0;
  for (const double friction : {50.0, 150.0, 400.0}) {
    const Trace trace = follow_sine(tuned(friction), amplitude, frequency, 2.0);
    // What friction adds to the error: around the second period's first reversal (t = 1.25 s), and late in
    // the stroke that follows (t = 1.45 … 1.5 s, full speed).
    auto added = [&](std::size_t from, std::size_t to) {
      double worst = 0.0;
      for (std::size_t k = from; k < to; ++k)
        worst = std::max(worst, std::abs(trace.actuator[k] - ideal.actuator[k]));
      return worst;
    };
    const std::size_t reversal = period_steps + quarter;
    const double at_reversal = added(reversal, reversal + quarter / 2);
    const double late_stroke = added(reversal + quarter - quarter / 5, reversal + quarter);
    EXPECT_GT(at_reversal, 3.0 * late_stroke) << friction;
    EXPECT_GT(at_reversal, 1.5 * previous_glitch) << friction;
    previous_glitch = at_reversal;
  }
}

// The actuator stays while the motor crosses the gap: after each reversal it lags the motor by exactly the
// backlash's width more than before (the lost motion), and never by more than half of it either way.
TEST(ServoImperfections, BacklashLosesExactlyItsWidthAtEveryReversal) {
  for (const double backlash : {0.002, 0.01, 0.05}) {
    LoopDesign design = one_drive();
    design.channels[0].backlash = backlash;
    const Trace trace = follow_sine(design, 2.0, 2.0, 1.0);
    double low = 0.0, high = 0.0;
    for (std::size_t k = 0; k < trace.motor.size(); ++k) {
      const double gap = trace.motor[k] - trace.actuator[k];
      ASSERT_LE(std::abs(gap), 0.5 * backlash + 1e-12);
      low = std::min(low, gap);
      high = std::max(high, gap);
    }
    EXPECT_NEAR(high - low, backlash, 1e-12);
    // At the top reversal (t = 0.625 s) the actuator lags the motor's turn: the motor comes back past the
    // actuator's peak by the width of the gap before it moves.
    const std::size_t top = static_cast<std::size_t>(std::lround(0.625 / kLoopS));
    const std::size_t after = static_cast<std::size_t>(std::lround(0.75 / kLoopS));
    const double actuator_peak =
        *std::max_element(trace.actuator.begin() + top - 200, trace.actuator.begin() + after);
    const double motor_peak = *std::max_element(trace.motor.begin() + top - 200, trace.motor.begin() + after);
    EXPECT_NEAR(motor_peak - actuator_peak, 0.5 * backlash, 1e-9);
  }
}

// Whole counts of the encoder: following a ramp the error is no longer smooth but wanders by about a count,
// and the wander grows with the count.
TEST(ServoImperfections, TheEncodersCountsLeaveANoiseFloorThatGrowsWithTheCount) {
  std::vector<double> spreads;
  for (const double resolution : {0.0, 0.001, 0.004}) {
    LoopDesign design = one_drive();
    design.channels[0].encoder_resolution = resolution;
    const Trace trace = follow(
        design, [](double t) { return 17.3 * t; }, [](double) { return 17.3; }, 0.5);
    // 17.3 mm/s: 4.325 counts of 1 µm per loop period, so the counted increments alternate.
    // The error's spread over the last 0.2 s (the transient long gone): its standard deviation.
    const std::size_t from = trace.reference.size() - static_cast<std::size_t>(0.2 / kLoopS);
    double mean = 0.0;
    for (std::size_t k = from; k < trace.reference.size(); ++k)
      mean += trace.reference[k] - trace.actuator[k];
    mean /= static_cast<double>(trace.reference.size() - from);
    double square = 0.0;
    for (std::size_t k = from; k < trace.reference.size(); ++k) {
      const double e = trace.reference[k] - trace.actuator[k] - mean;
      square += e * e;
    }
    spreads.push_back(std::sqrt(square / static_cast<double>(trace.reference.size() - from)));
  }
  EXPECT_LT(spreads[0], 1e-9);          // exact measurement: a constant error on a ramp
  EXPECT_GT(spreads[1], 0.05 * 0.001);  // a noise floor of the order of the count
  EXPECT_LT(spreads[1], 2.0 * 0.001);
  EXPECT_GT(spreads[2], 2.0 * spreads[1]);  // four times the count: clearly more
}

// Acting on older samples: the loop loses phase margin, so a step's overshoot grows with the delay; a loop
// tuned for no delay goes unstable once the delay is long against the current loop's lag.
TEST(ServoImperfections, ASamplingDelayGrowsTheOvershootAndFinallyDestabilises) {
  const double step_mm = 0.1;
  std::vector<double> overshoots;
  for (const int delay : {0, 2, 4}) {
    LoopDesign design = one_drive();
    design.sample_delay_periods = delay;
    const Trace trace = follow(
        design, [&](double t) { return t > 0.0 ? step_mm : 0.0; }, [](double) { return 0.0; }, 0.4);
    const double peak = *std::max_element(trace.actuator.begin(), trace.actuator.end());
    overshoots.push_back(peak - step_mm);
    EXPECT_NEAR(trace.actuator.back(), step_mm, 1e-6) << delay;  // lightly damped, but it settles
  }
  EXPECT_GT(overshoots[1], overshoots[0] + 0.01 * step_mm);
  EXPECT_GT(overshoots[2], overshoots[1] + 0.01 * step_mm);
  // A fast current loop (T_μ = 2 loop periods) with eight periods of delay: the error grows without bound.
  LoopDesign fast = one_drive(2.0 * kLoopS);
  fast.sample_delay_periods = 8;
  const Trace unstable = follow_sine(fast, 1.0, 2.0, 0.5);
  const double late = max_abs_error(unstable, unstable.reference.size() - 100, unstable.reference.size());
  EXPECT_TRUE(!std::isfinite(late) || late > 1e3) << late;
  // ... and without the delay the same loop follows.
  LoopDesign fast_now = one_drive(2.0 * kLoopS);
  const Trace stable = follow_sine(fast_now, 1.0, 2.0, 0.5);
  EXPECT_LT(max_abs_error(stable, stable.reference.size() - 100, stable.reference.size()), 0.1);
}

// The static characteristic: a table that is the linear law changes nothing; a dead zone in it stops P loops
// short as friction does; a flat top caps the force however large the command.
TEST(ServoImperfections, TheStaticCharacteristicsDeadZoneAndSaturationShow) {
  const LoopDesign ideal = one_drive();
  const double unit = ideal.channels[0].force_per_command;  // k_μ F_base: the linear law's force for u = 1
  auto with = [&](std::initializer_list<std::array<double, 2>> points) {
    LoopDesign design = one_drive();
    int k = 0;
    for (const auto& p : points) design.channels[0].characteristic[k++] = {p[0], p[1] * unit};
    design.channels[0].characteristic_points = k;
    return design;
  };
  const Trace linear_law = follow_sine(with({{0.0, 0.0}, {100.0, 100.0}}), 5.0, 2.0, 0.6);
  const Trace none = follow_sine(ideal, 5.0, 2.0, 0.6);
  for (std::size_t k = 0; k < none.actuator.size(); ++k)
    ASSERT_NEAR(linear_law.actuator[k], none.actuator[k], 1e-9);

  // A dead zone of 0.02 in u: the loops stop where K_w·k_p·e < 0.02·k_μ F_base.
  const double target = 1.0;
  const SmoothMove move_to{target};
  auto reference = [&](double t) { return move_to.position(t); };
  auto speed = [&](double t) { return move_to.speed(t); };
  const ChannelGains& g = ideal.channels[0];
  const Trace dead = follow(with({{0.0, 0.0}, {0.02, 0.0}, {100.0, 99.98}}), reference, speed, 0.5);
  const double zone = 0.02 * unit / (g.speed_gain * g.position_gain_per_s);
  EXPECT_LE(std::abs(target - dead.actuator.back()), zone * (1.0 + 1e-6));
  EXPECT_GT(std::abs(target - dead.actuator.back()), 0.01 * zone);

  // Saturation at u = 0.01: a fast move takes longer, the force never past the cap.
  const double cap = 0.01 * unit;
  LoopDesign flat = with({{0.0, 0.0}, {0.01, 0.01}, {100.0, 0.01}});
  ServoSimulator simulator(flat, kLoopS);
  simulator.reset(DriveVector::Zero());
  DriveVector r = DriveVector::Zero(), v = DriveVector::Zero();
  double peak_force = 0.0, worst_error = 0.0;
  for (int k = 1; k <= 2000; ++k) {
    r[0] = reference(k * kLoopS);
    v[0] = speed(k * kLoopS);
    simulator.step(r, v);
    peak_force = std::max(peak_force, std::abs(simulator.force()[0]));
    worst_error = std::max(worst_error, std::abs(r[0] - simulator.actuator_position()[0]));
  }
  EXPECT_LE(peak_force, cap * (1.0 + 1e-12));
  EXPECT_GT(worst_error, 10.0 * max_abs_error(follow(ideal, reference, speed, 0.5), 0, 2000));
}

}  // namespace
}  // namespace pkm::servo
