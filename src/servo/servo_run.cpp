#include "servo/servo_run.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "servo/commanded_path.hpp"

namespace pkm::servo {
namespace {

constexpr std::size_t kServoListedLines = 20;
constexpr std::size_t kServoWorstLines = 10;
constexpr int kServoStabilitySamples = 400;

// The inverse of the plant's inertia as the run models it: the full matrix, or its diagonal alone.
DriveMatrix servo_inverse_inertia(const DriveMatrix& inertia, int drives, bool coupled) {
  DriveMatrix out = DriveMatrix::Zero();
  if (coupled) {
    out.topLeftCorner(drives, drives) = inertia.topLeftCorner(drives, drives).inverse();
  } else {
    for (int j = 0; j < drives; ++j) out(j, j) = 1.0 / inertia(j, j);
  }
  return out;
}

void servo_add_line(std::vector<int>& lines, int line) {
  if (std::find(lines.begin(), lines.end(), line) != lines.end()) return;
  if (lines.size() < kServoListedLines)
    lines.insert(std::upper_bound(lines.begin(), lines.end(), line), line);
}

// Balances `map` by a diagonal similarity (Parlett–Reinsch): the loop's states span many decades (positions
// in mm, forces of 10⁸ N per mm of error at T_μ = 10 µs), and the eigenvalues of the unbalanced matrix lose
// digits enough to misjudge its stability.
void servo_balance(Eigen::MatrixXd& map) {
  const Eigen::Index n = map.rows();
  for (int sweep = 0; sweep < 40; ++sweep) {
    bool changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double column = map.col(i).cwiseAbs().sum() - std::abs(map(i, i));
      const double row = map.row(i).cwiseAbs().sum() - std::abs(map(i, i));
      if (!(column > 0.0) || !(row > 0.0)) continue;
      const double f = std::sqrt(row / column);
      if (std::abs(std::log(f)) < 0.01) continue;
      map.col(i) *= f;
      map.row(i) /= f;
      changed = true;
    }
    if (!changed) break;
  }
}

}  // namespace

Result<int> loop_steps_per_period(const Machine& machine, double period_s) {
  const double loop_s = machine.servo.loop_period_s > 0.0 ? machine.servo.loop_period_s : period_s;
  const double ratio = period_s / loop_s;
  const int steps = static_cast<int>(std::lround(ratio));
  if (steps < 1 || std::abs(ratio - steps) > 1e-6 * ratio) {
    const int line = machine.servo.loop_period_line;
    return Error{ErrorCode::bad_input,
                 fmt::format("{}:{}: servo.loop_period_ms: {} ms does not divide the servo period {} ms",
                             machine.source, line, loop_s * 1e3, period_s * 1e3),
                 ErrorLocation{machine.source, line, 0, "servo.loop_period_ms"}};
  }
  return steps;
}

Status check_stability(const Machine& machine, const LoopDesign& design, const ServoPlant& plant,
                       const ServoRunInput& input, int steps_per_period, const ServoRunOptions& options) {
  // The limits and the drives' non-linear imperfections off (friction, backlash, the encoder's counts, the
  // static characteristic): the loop period's map is then linear in the state. A sampling delay stays: it is
  // linear, and it is what most often makes a loop unstable.
  LoopDesign linear = design;
  for (int j = 0; j < design.drives; ++j) {
    ChannelGains& g = linear.channels[j];
    g.error_max = std::numeric_limits<double>::infinity();
    g.command_max = std::numeric_limits<double>::infinity();
    g.friction_coulomb = g.friction_static = g.friction_viscous = 0.0;
    g.backlash = g.encoder_resolution = 0.0;
    g.characteristic_points = 0;
  }
  const double period_s = input.period_s / steps_per_period;
  ServoSimulator simulator(linear, period_s);
  const std::size_t samples = plant.inertia.size();
  const std::size_t every = std::max<std::size_t>(1, samples / kServoStabilitySamples);
  // The states that carry the loops' dynamics: each drive's position, speed and force, and its speed integral
  // and filtered reference where the tuning has them (otherwise they hold nothing from one step to the next).
  std::vector<int> states;
  for (int kind = 0; kind < 5; ++kind) {
    for (int j = 0; j < design.drives; ++j) {
      const ChannelGains& g = design.channels[j];
      if ((kind == 3 && !(g.speed_integral_s > 0.0)) || (kind == 4 && !(g.reference_filter_s > 0.0)))
        continue;
      states.push_back(kind * kMaxActuators + j);
    }
  }
  // The samples waiting out the delay.
  for (int age = 0; age < std::min(design.sample_delay_periods, kMaxSampleDelay); ++age) {
    for (int j = 0; j < design.drives; ++j) {
      states.push_back(ServoSimulator::kDelayedPositionState + age * kMaxActuators + j);
      states.push_back(ServoSimulator::kDelayedSpeedState + age * kMaxActuators + j);
    }
  }
  const int n = static_cast<int>(states.size());
  const DriveVector zero = DriveVector::Zero();
  for (std::size_t i = 0; i < samples; i += every) {
    simulator.set_inverse_inertia(servo_inverse_inertia(plant.inertia[i], design.drives, options.coupled));
    Eigen::MatrixXd map(n, n);
    for (int c = 0; c < n; ++c) {
      simulator.set_state(ServoSimulator::StateVector::Unit(states[static_cast<std::size_t>(c)]));
      simulator.step(zero, zero);
      const ServoSimulator::StateVector after = simulator.state();
      for (int r = 0; r < n; ++r) map(r, c) = after[states[static_cast<std::size_t>(r)]];
    }
    servo_balance(map);
    const Eigen::EigenSolver<Eigen::MatrixXd> eigen(map, false);
    const auto& values = eigen.eigenvalues();
    int worst = 0;
    for (int c = 1; c < n; ++c) {
      if (std::abs(values[c]) > std::abs(values[worst])) worst = c;
    }
    const double radius = std::abs(values[worst]);
    if (radius >= 1.0 - 1e-12 || !std::isfinite(radius)) {
      const std::size_t tick = std::min(i * static_cast<std::size_t>(plant.stride), input.line.size() - 1);
      // The drive whose states the unstable mode moves most.
      const Eigen::EigenSolver<Eigen::MatrixXd> vectors(map, true);
      const Eigen::VectorXd mode = vectors.eigenvectors().col(worst).cwiseAbs();
      int drive = 0;
      double largest = -1.0;
      for (int c = 0; c < n; ++c) {
        if (mode[c] > largest) {
          largest = mode[c];
          drive = states[static_cast<std::size_t>(c)] % kMaxActuators;
        }
      }
      const DriveServo& d = machine.servo.drives[drive];
      const int line = machine.servo.tuning == ServoTuning::explicit_gains ? d.speed_gain_line : d.line;
      const int delay = design.sample_delay_periods;
      return Error{ErrorCode::bad_input,
                   fmt::format("{}:{}: servo.drives[{}]: the loops are unstable at program line {} (spectral "
                               "radius {:.4f} of the {} ms loop period; {} tuning{}): lower the gains or the "
                               "loop period{}",
                               machine.source, line, drive, input.line[tick], radius, period_s * 1e3,
                               to_string(machine.servo.tuning),
                               delay > 0 ? fmt::format(", a sample delay of {} periods", delay) : "",
                               delay > 0 ? ", or the delay (servo.sample_delay_periods)" : ""),
                   ErrorLocation{machine.source, line, 0, fmt::format("servo.drives[{}]", drive)}};
    }
  }
  return ok_status();
}

namespace {

// The coupling check along the run: Σ_k |A'_ik| / J_m,i per drive, its largest and the lines above the limit.
void check_coupling(const Machine& machine, const ServoPlant& plant, const ServoRunInput& input, int drives,
                    ServoSummary& summary) {
  const std::size_t ticks = input.time_s.size();
  const ActuatorVector motors = motor_inertia(machine.servo, drives);
  for (std::size_t i = 0; i < plant.machine_inertia.size(); ++i) {
    const DriveVector ratios = coupling_ratios(plant.machine_inertia[i], motors, drives);
    const int line = input.line[std::min(i * static_cast<std::size_t>(plant.stride), ticks - 1)];
    for (int j = 0; j < drives; ++j) {
      DriveServoSummary& d = summary.drive[j];
      if (ratios[j] > d.max_coupling_ratio) {
        d.max_coupling_ratio = ratios[j];
        d.max_coupling_line = line;
      }
      if (ratios[j] >= kCouplingRatioLimit) servo_add_line(d.coupled_lines, line);
    }
  }
}

// The contour error of simulated drive positions (FK, then the nearest point of the commanded path) and its
// statistics in the summary.
class ContourMeasure {
 public:
  ContourMeasure(const Mechanism& mechanism, const ServoRunInput& input, int drives, ServoSummary& summary)
      : mechanism_(mechanism),
        path_(commanded_path(input, mechanism.controlled_axes())),
        axes_(mechanism.controlled_axes()),
        ticks_(input.time_s.size()),
        workspace_(mechanism.make_fk_workspace()),
        guess_(input.pose[0]),
        actuators_(drives),
        summary_(summary) {}
  void set_window(std::size_t window) { window_ = window; }

  // The error at time `time_s`, searching the path back from tick `k`; `lag_s` how far behind in time (NaN
  // where FK failed or the path nearly stands still).
  double measure(const DriveVector& position, std::size_t k, double time_s, double& lag_s) {
    actuators_ = position.head(actuators_.size());
    auto fk = mechanism_.forward_warm(actuators_, guess_, FkOptions{}, *workspace_);
    if (!fk) {
      ++summary_.fk_failures;
      lag_s = std::numeric_limits<double>::quiet_NaN();
      return std::numeric_limits<double>::quiet_NaN();
    }
    guess_ = fk->pose;
    const std::size_t first = k > window_ ? 2 * (k - window_) : 0;
    const std::size_t last = 2 * std::min(k + 1, ticks_ - 1);
    const NearestOnPath nearest =
        nearest_on_path(path_, first, last, controlled_point(fk->pose.position_mm, axes_));
    const double distance = nearest.distance_mm, at_s = nearest.time_s;
    // Where the path nearly stands still a tiny error (a static one under gravity, say) is a long time: the
    // lag is given only where the commanded speed is at least a quarter of the run's fastest.
    lag_s = path_.speed[k] >= 0.25 * path_.fastest ? time_s - at_s : std::numeric_limits<double>::quiet_NaN();
    return distance;
  }

  void record(double error_mm, double lag_s, double time_s, int line) {
    if (!std::isfinite(error_mm)) return;
    squares_ += error_mm * error_mm;
    ++count_;
    if (error_mm > summary_.max_contour_error_mm) {
      summary_.max_contour_error_mm = error_mm;
      summary_.max_contour_time_s = time_s;
      summary_.max_contour_line = line;
    }
    if (std::isfinite(lag_s)) summary_.max_lag_s = std::max(summary_.max_lag_s, lag_s);
    double& worst = worst_by_line_[line];
    worst = std::max(worst, error_mm);
  }

  // The RMS and the lines of the largest errors into the summary.
  void finish() {
    if (count_ > 0) summary_.rms_contour_error_mm = std::sqrt(squares_ / count_);
    std::vector<std::pair<int, double>> lines(worst_by_line_.begin(), worst_by_line_.end());
    std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    if (lines.size() > kServoWorstLines) lines.resize(kServoWorstLines);
    summary_.worst_lines = std::move(lines);
  }

 private:
  const Mechanism& mechanism_;
  CommandedPath path_;
  AxisMask axes_;
  std::size_t ticks_;
  std::size_t window_ = 0;
  std::unique_ptr<FkWorkspace> workspace_;
  Pose guess_;
  ActuatorVector actuators_;
  ServoSummary& summary_;
  std::map<int, double> worst_by_line_;
  double squares_ = 0.0;
  long count_ = 0;
};

// One servo period of the loops from `previous` to `setpoint`: the loop steps with the reference ramped
// between them, the limits that acted counted; returns the actuators' positions at mid-period (the motors'
// less any backlash not taken up: what moves the machine).
DriveVector run_period(ServoSimulator& simulator, const DriveVector& previous, const DriveVector& setpoint,
                       double period_s, int steps_per_period, ServoTick& tick, ServoSummary& summary) {
  const DriveVector speed = (setpoint - previous) / period_s;
  DriveVector mid = previous;
  for (int i = 0; i < steps_per_period; ++i) {
    const DriveVector reference =
        previous + (static_cast<double>(i) / steps_per_period) * (setpoint - previous);
    simulator.step(reference, speed);
    tick.clamps.error |= simulator.clamps().error;
    tick.clamps.command |= simulator.clamps().command;
    for (int j = 0; j < summary.drives; ++j) {
      if (simulator.clamps().error & (1u << j)) ++summary.drive[j].error_clamps;
      if (simulator.clamps().command & (1u << j)) ++summary.drive[j].command_clamps;
    }
    if (2 * i + 1 == steps_per_period) mid = simulator.mid_actuator_position();
    if (2 * (i + 1) == steps_per_period) mid = simulator.actuator_position();
  }
  return mid;
}

// The following errors, peaks and clamped lines of a tick into the summary; `squares` the sums for the RMS.
void record_following(const ServoTick& tick, const ServoSimulator& simulator, std::vector<double>& squares,
                      ServoSummary& summary) {
  for (int j = 0; j < summary.drives; ++j) {
    DriveServoSummary& d = summary.drive[j];
    const double error = (*tick.setpoint)[j] - simulator.actuator_position()[j];
    squares[j] += error * error;
    if (std::abs(error) > d.max_following_error) {
      d.max_following_error = std::abs(error);
      d.max_following_time_s = tick.time_s;
      d.max_following_line = tick.line;
    }
    d.peak_force = std::max(d.peak_force, std::abs(simulator.force()[j]));
    d.peak_command = std::max(d.peak_command, std::abs(simulator.command()[j]));
    if ((tick.clamps.error | tick.clamps.command) & (1u << j)) servo_add_line(d.clamp_lines, tick.line);
  }
}

}  // namespace

Result<ServoSummary> run_servo(const Machine& machine, const LoopDesign& design, const ServoPlant& plant,
                               const ServoRunInput& input, int steps_per_period,
                               const ServoRunOptions& options,
                               const std::function<Status(const ServoTick&)>& on_tick) {
  const int m = design.drives;
  const std::size_t ticks = input.time_s.size();
  ServoSummary summary;
  summary.drives = m;
  summary.period_s = input.period_s;
  summary.loop_period_s = input.period_s / steps_per_period;
  summary.coupled = options.coupled;
  summary.has_machine_dynamics = plant.has_machine_dynamics;
  if (ticks == 0) return summary;
  check_coupling(machine, plant, input, m, summary);
  ContourMeasure contour(*machine.mechanism, input, m, summary);
  contour.set_window(search_window(design, input));

  ServoSimulator simulator(design, summary.loop_period_s);
  simulator.set_load(plant.load[0]);
  std::size_t inertia_sample = 0;
  simulator.set_inverse_inertia(servo_inverse_inertia(plant.inertia[0], m, options.coupled));
  DriveVector start = DriveVector::Zero();
  start.head(m) = input.setpoint[0];
  simulator.reset(start);

  std::vector<double> squares(m, 0.0);
  DriveVector setpoint = start, previous = start;
  for (std::size_t k = 0; k < ticks; ++k) {
    ServoTick tick;
    if (k > 0) {
      previous.head(m) = input.setpoint[k - 1];
      setpoint.head(m) = input.setpoint[k];
      if (const std::size_t sample = (k - 1) / static_cast<std::size_t>(plant.stride);
          sample != inertia_sample && sample < plant.inertia.size()) {
        inertia_sample = sample;
        simulator.set_inverse_inertia(servo_inverse_inertia(plant.inertia[sample], m, options.coupled));
      }
      simulator.set_load(0.5 * (plant.load[k - 1] + plant.load[k]));
      const DriveVector mid =
          run_period(simulator, previous, setpoint, input.period_s, steps_per_period, tick, summary);
      if (!simulator.finite()) {
        return make_error(ErrorCode::not_converged,
                          fmt::format("program line {} (t = {:.4f} s): the servo loops diverged",
                                      input.line[k], input.time_s[k]));
      }
      double mid_lag = 0.0;
      const double mid_s = input.time_s[k] - 0.5 * input.period_s;
      contour.record(contour.measure(mid, k, mid_s, mid_lag), mid_lag, mid_s, input.line[k]);
    }
    tick.time_s = input.time_s[k];
    tick.line = input.line[k];
    tick.drives = m;
    tick.setpoint = &setpoint;
    tick.position = &simulator.actuator_position();
    tick.force = &simulator.force();
    tick.command = &simulator.command();
    tick.contour_error_mm = contour.measure(simulator.actuator_position(), k, tick.time_s, tick.lag_s);
    contour.record(tick.contour_error_mm, tick.lag_s, tick.time_s, tick.line);
    record_following(tick, simulator, squares, summary);
    if (on_tick) {
      if (Status sent = on_tick(tick); !sent) return sent.error();
    }
  }
  summary.ticks = static_cast<long>(ticks);
  for (int j = 0; j < m; ++j)
    summary.drive[j].rms_following_error = std::sqrt(squares[j] / static_cast<double>(ticks));
  contour.finish();
  return summary;
}

}  // namespace pkm::servo
