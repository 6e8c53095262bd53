#include "servo/loop_analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "servo/servo_simulator.hpp"

namespace pkm::servo {
namespace {

using Complex = std::complex<double>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The open loops of one channel at a point s (continuous) or z (sampled), and the closed ones from them.
struct ChannelLoops {
  Complex speed_open, speed_closed, position_open, position_closed;
};

ChannelLoops continuous_loops(const ChannelGains& g, Complex s) {
  const Complex regulator =
      g.speed_gain * (g.speed_integral_s > 0.0 ? 1.0 + 1.0 / (g.speed_integral_s * s) : 1.0);
  const Complex plant = 1.0 / ((g.lag_s * s + 1.0) * g.inertia * s);  // force command → speed
  const Complex filter = g.reference_filter_s > 0.0 ? 1.0 / (g.reference_filter_s * s + 1.0) : Complex(1.0);
  ChannelLoops out;
  out.speed_open = regulator * plant;
  const Complex inner = out.speed_open / (1.0 + out.speed_open);
  out.speed_closed = filter * inner;
  out.position_open = g.position_gain_per_s * out.speed_closed / s;
  out.position_closed = out.position_open / (1.0 + out.position_open);
  return out;
}

// The plant from the held force command to (force, speed, position) over one period h: exactly the
// simulator's (the lag's closed form and its integrals).
struct SampledPlant {
  Eigen::Matrix3d phi;
  Eigen::Vector3d gamma;
};

SampledPlant sampled_plant(const ChannelGains& g, double h) {
  const double alpha = std::exp(-h / g.lag_s);
  const double c1 = g.lag_s * (1.0 - alpha), c2 = g.lag_s * (h - c1);
  SampledPlant p;
  p.phi << alpha, 0.0, 0.0, c1 / g.inertia, 1.0, 0.0, c2 / g.inertia, h, 1.0;
  p.gamma << 1.0 - alpha, (h - c1) / g.inertia, (0.5 * h * h - c2) / g.inertia;
  return p;
}

ChannelLoops sampled_loops(const ChannelGains& g, double h, Complex z) {
  const SampledPlant p = sampled_plant(g, h);
  const Eigen::Matrix3cd resolvent = (z * Eigen::Matrix3cd::Identity() - p.phi.cast<Complex>()).inverse();
  const Eigen::Vector3cd response = resolvent * p.gamma.cast<Complex>();
  const Complex to_speed = response[1], to_position = response[2];
  const Complex regulator =
      g.speed_gain * (g.speed_integral_s > 0.0 ? 1.0 + (h / g.speed_integral_s) / (z - 1.0) : Complex(1.0));
  const double keep = g.reference_filter_s > 0.0 ? std::exp(-h / g.reference_filter_s) : 0.0;
  const Complex filter = (1.0 - keep) * z / (z - keep);
  ChannelLoops out;
  out.speed_open = regulator * to_speed;
  out.speed_closed = filter * out.speed_open / (1.0 + out.speed_open);
  const Complex reference_to_position = filter * regulator * to_position / (1.0 + out.speed_open);
  out.position_open = g.position_gain_per_s * reference_to_position;
  out.position_closed = out.position_open / (1.0 + out.position_open);
  return out;
}

// Margins of an open loop over [w_min, w_max] (rad/s), its phase unwrapped from the branch nearest the
// low-frequency asymptote −90° per integrator.
StabilityMargins margins_of(const std::function<Complex(double)>& open, double w_min, double w_max,
                            int integrators) {
  constexpr int kGrid = 4000;
  StabilityMargins out;
  out.gain_margin_db = std::numeric_limits<double>::infinity();
  out.phase_margin_deg = kNaN;
  double previous_w = w_min, previous_phase = 0.0, previous_gain = 0.0;
  bool gain_found = false, phase_found = false;
  for (int i = 0; i <= kGrid; ++i) {
    const double w = w_min * std::pow(w_max / w_min, static_cast<double>(i) / kGrid);
    const Complex value = open(w);
    double phase = std::arg(value);
    const double target = i == 0 ? -0.5 * std::numbers::pi * integrators : previous_phase;
    phase += 2.0 * std::numbers::pi * std::round((target - phase) / (2.0 * std::numbers::pi));
    const double gain = std::abs(value);
    if (i > 0) {
      // Linear interpolation in log ω between grid points is finer than the figures need (4000 points).
      if (!gain_found && previous_gain >= 1.0 && gain < 1.0) {
        const double f = std::log(previous_gain) / (std::log(previous_gain) - std::log(gain));
        const double w_c = previous_w * std::pow(w / previous_w, f);
        const double phase_c = previous_phase + f * (phase - previous_phase);
        out.phase_margin_deg = 180.0 + phase_c * 180.0 / std::numbers::pi;
        out.crossover_hz = w_c / (2.0 * std::numbers::pi);
        gain_found = true;
      }
      if (!phase_found && previous_phase > -std::numbers::pi && phase <= -std::numbers::pi) {
        const double f = (previous_phase + std::numbers::pi) / (previous_phase - phase);
        const double w_p = previous_w * std::pow(w / previous_w, f);
        const double gain_p =
            std::exp(std::log(previous_gain) + f * (std::log(gain) - std::log(previous_gain)));
        out.gain_margin_db = -20.0 * std::log10(gain_p);
        out.phase_crossover_hz = w_p / (2.0 * std::numbers::pi);
        phase_found = true;
      }
    }
    previous_w = w;
    previous_phase = phase;
    previous_gain = gain;
  }
  return out;
}

// Step response of one channel alone, simulated at period h: the speed loop (a unit speed reference) or the
// position loop (a unit position step). The loops' own response: no limits, no friction, backlash or
// encoder counts (their effects are the run's, not the tuning's).
StepMetrics step_of(const ChannelGains& gains, double h, bool speed_loop, double horizon_s) {
  ChannelGains g = gains;
  g.error_max = std::numeric_limits<double>::infinity();
  g.command_max = std::numeric_limits<double>::infinity();
  g.friction_coulomb = g.friction_static = g.friction_viscous = 0.0;
  g.backlash = g.encoder_resolution = 0.0;
  g.characteristic_points = 0;
  if (speed_loop) {
    g.position_gain_per_s = 0.0;
    g.velocity_feedforward = 1.0;
  } else {
    g.velocity_feedforward = 0.0;
  }
  LoopDesign design;
  design.drives = 1;
  design.channels[0] = g;
  ServoSimulator simulator(design, h);
  simulator.reset(DriveVector::Zero());
  DriveVector reference = DriveVector::Zero(), speed = DriveVector::Zero();
  (speed_loop ? speed : reference)[0] = 1.0;
  StepMetrics out;
  double peak = -std::numeric_limits<double>::infinity();
  const long steps = static_cast<long>(std::ceil(horizon_s / h));
  double last_outside_s = 0.0;
  auto sample = [&](double value, double time_s) {
    if (value > peak) {
      peak = value;
      out.peak_time_s = time_s;
    }
    if (std::abs(value - 1.0) > 0.02) last_outside_s = time_s;
  };
  for (long k = 0; k < steps; ++k) {
    simulator.step(reference, speed);
    if (speed_loop) {
      sample(simulator.speed()[0], (k + 1) * h);
    } else {
      sample(simulator.mid_position()[0], (k + 0.5) * h);
      sample(simulator.position()[0], (k + 1) * h);
    }
  }
  out.overshoot_pct = std::max(0.0, 100.0 * (peak - 1.0));
  out.settling_s = last_outside_s;
  return out;
}

double slowest_time_s(const ChannelGains& g) {
  return std::max({g.lag_s, g.speed_integral_s, g.reference_filter_s,
                   g.position_gain_per_s > 0.0 ? 1.0 / g.position_gain_per_s : 0.0});
}

}  // namespace

ChannelAnalysis analyse_channel(const ChannelGains& g, double loop_period_s) {
  ChannelAnalysis out;
  const double slowest = slowest_time_s(g);
  const double horizon_s = 30.0 * slowest;
  // The continuous loops' steps, simulated at a period far below every time constant (the overshoot within
  // 0.01 pp of the closed forms').
  const double fine_s = std::min(g.lag_s, loop_period_s) / 1000.0;
  out.speed_continuous.step = step_of(g, fine_s, true, horizon_s);
  out.position_continuous.step = step_of(g, fine_s, false, horizon_s);
  out.speed_sampled.step = step_of(g, loop_period_s, true, horizon_s);
  out.position_sampled.step = step_of(g, loop_period_s, false, horizon_s);

  const int speed_integrators = g.speed_integral_s > 0.0 ? 2 : 1;
  const double w_min = 1e-3 / slowest, w_max = 1e4 / g.lag_s;
  out.speed_continuous.margins =
      margins_of([&](double w) { return continuous_loops(g, Complex(0.0, w)).speed_open; }, w_min, w_max,
                 speed_integrators);
  out.position_continuous.margins = margins_of(
      [&](double w) { return continuous_loops(g, Complex(0.0, w)).position_open; }, w_min, w_max, 1);
  const double nyquist = std::numbers::pi / loop_period_s * (1.0 - 1e-9);
  auto z_of = [&](double w) { return std::polar(1.0, w * loop_period_s); };
  out.speed_sampled.margins =
      margins_of([&](double w) { return sampled_loops(g, loop_period_s, z_of(w)).speed_open; }, w_min,
                 nyquist, speed_integrators);
  out.position_sampled.margins = margins_of(
      [&](double w) { return sampled_loops(g, loop_period_s, z_of(w)).position_open; }, w_min, nyquist, 1);
  out.ramp_error_per_speed_s =
      g.position_gain_per_s > 0.0 ? (1.0 - g.velocity_feedforward) / g.position_gain_per_s : kNaN;
  return out;
}

LoopResponse loop_response(const ChannelGains& g, double loop_period_s, double frequency_hz) {
  LoopResponse out;
  out.frequency_hz = frequency_hz;
  const double w = 2.0 * std::numbers::pi * frequency_hz;
  const ChannelLoops c = continuous_loops(g, Complex(0.0, w));
  out.speed_open = c.speed_open;
  out.speed_closed = c.speed_closed;
  out.position_open = c.position_open;
  out.position_closed = c.position_closed;
  if (w * loop_period_s < std::numbers::pi) {
    const ChannelLoops s = sampled_loops(g, loop_period_s, std::polar(1.0, w * loop_period_s));
    out.speed_open_sampled = s.speed_open;
    out.speed_closed_sampled = s.speed_closed;
    out.position_open_sampled = s.position_open;
    out.position_closed_sampled = s.position_closed;
  } else {
    const Complex nan(kNaN, kNaN);
    out.speed_open_sampled = out.speed_closed_sampled = out.position_open_sampled =
        out.position_closed_sampled = nan;
  }
  return out;
}

std::vector<LoopResponse> bode_data(const ChannelGains& g, double loop_period_s, double f_min_hz,
                                    double f_max_hz, int points) {
  std::vector<LoopResponse> out;
  out.reserve(static_cast<std::size_t>(std::max(points, 2)));
  for (int i = 0; i < std::max(points, 2); ++i) {
    const double f =
        f_min_hz * std::pow(f_max_hz / f_min_hz, static_cast<double>(i) / (std::max(points, 2) - 1));
    out.push_back(loop_response(g, loop_period_s, f));
  }
  return out;
}

}  // namespace pkm::servo
