#pragma once
// Each drive's speed and position loops analysed on their own (the drive's own inertia, no coupling):
// step responses, stability margins and frequency responses, for the continuous loops of the design and
// for the loops as sampled at the drive's loop period (zero-order hold on the force command, regulators
// acting on the sampled speed and position; loop_design.hpp, servo_simulator.hpp). The
// motion-control textbook, §2.7.3: the technical optimum gives a speed loop with 4.3 % overshoot (e^−π)
// and a phase margin of 65.5°, and a position loop (3rd-order Butterworth) with 8.15 % overshoot, 2 %
// settling at 13.3 T_μ, phase margin 60.5° and gain margin 12.04 dB; its ramp following error is 4 T_μ v.
#include <complex>
#include <vector>

#include "servo/loop_design.hpp"

namespace pkm::servo {

struct StepMetrics {
  double overshoot_pct = 0.0;
  double settling_s = 0.0;  ///< last time the response is outside ±2 % of the final value
  double peak_time_s = 0.0;
};

struct StabilityMargins {
  double phase_margin_deg = 0.0;
  double crossover_hz = 0.0;    ///< where the open loop's gain is 1
  double gain_margin_db = 0.0;  ///< ∞ where the phase never falls through −180°
  double phase_crossover_hz = 0.0;
};

struct LoopFigures {
  StepMetrics step;
  StabilityMargins margins;
};

/// The speed loop (reference → speed, its set-point filter included) and the position loop (reference →
/// position), continuous and sampled, and the steady following error on a ramp per unit speed.
struct ChannelAnalysis {
  LoopFigures speed_continuous, speed_sampled, position_continuous, position_sampled;
  double ramp_error_per_speed_s = 0.0;  ///< (1 − feed-forward)/k_p
};

/// `loop_period_s` > 0: the sampled loops' period.
ChannelAnalysis analyse_channel(const ChannelGains& gains, double loop_period_s);

/// Frequency responses of one channel's loops at one frequency; the sampled ones are NaN above the Nyquist
/// frequency.
struct LoopResponse {
  double frequency_hz = 0.0;
  std::complex<double> speed_open, speed_closed, position_open, position_closed;
  std::complex<double> speed_open_sampled, speed_closed_sampled, position_open_sampled,
      position_closed_sampled;
};

LoopResponse loop_response(const ChannelGains& gains, double loop_period_s, double frequency_hz);

/// `points` frequencies spaced logarithmically over [f_min, f_max] (Hz).
std::vector<LoopResponse> bode_data(const ChannelGains& gains, double loop_period_s, double f_min_hz,
                                    double f_max_hz, int points);

}  // namespace pkm::servo
