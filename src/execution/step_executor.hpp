#pragma once
// The per-period core of executing planned motion on a controller (LinuxCNC's servo thread runs it through
// pkm's HAL component, docs/linuxcnc.md): it takes the nominal motion period by period as it streams in —
// each drive's ideal value and its whole-step position at the end of every nominal period, as `pkm
// interpolate` computes them — and releases one period of drive positions per servo period, time-scaled by
// the operator's feed override, feed hold and abort (override_law.hpp).
//
// At K = 1 (no override, no hold) τ stays on the nominal grid and the released positions are the nominal
// whole steps themselves: the interpolator's step-exact output (its discreteness correction included)
// reaches the drives unchanged. Off the grid the drives' set point is the cubic (Catmull–Rom) interpolant of
// the ideal values at τ, rounded to whole steps.
//
// The window of nominal periods is bounded (kWindow): memory does not grow with the program. So that the
// motion can always stop inside what it has been given, the executor holds (K → 0) whenever the periods
// ahead of τ are fewer than its stopping distance, and resumes when they come: a stream that runs dry slows
// the machine within its limits instead of stopping it dead. A nominal position outside the drives'
// software stops (the actuator ranges) is never released: the executor stops before it, as for an abort,
// and reports the stop with the program line.
//
// Nothing here allocates; every call is bounded in time (real-time safe).
#include <array>
#include <cstdint>

#include "execution/override_law.hpp"
#include "kinematics/actuator_vector.hpp"

namespace pkm::execution {

using StepArray = std::array<std::int64_t, kMaxActuators>;
using ValueArray = std::array<double, kMaxActuators>;

/// One nominal period: the drives at its end, ideal (continuous, in steps) and as whole steps.
struct NominalPeriod {
  ValueArray ideal_steps{};
  StepArray position_steps{};
  int line = 0;
};

struct ExecutionControls {
  double override_factor = 1.0;  ///< the operator's feed override, 0 … max_override (1 = 100 %)
  bool hold = false;             ///< feed hold: stop along the path, resume when released
  bool abort = false;            ///< stop along the path and drop the rest of the program
};

enum class ExecutionState {
  idle,              ///< no program
  running,           ///< moving (or waiting at K = 0 for the operator)
  starved,           ///< slowed or stopped because the stream has not delivered enough periods ahead
  finished,          ///< the last nominal period has been released
  aborted,           ///< stopped by an abort; the rest of the program is dropped
  stopped_at_limit,  ///< stopped before a position outside the software stops (fault_line names it)
};

struct ExecutorSettings {
  int drives = 6;
  double period_s = 0.001;
  double max_override = 1.2;  ///< the largest K the operator can ask for
  OverrideRates rates;        ///< execution_headroom.hpp
  /// Software stops in actuator space (whole steps), inclusive.
  StepArray min_position_steps{};
  StepArray max_position_steps{};
};

/// One released servo period.
struct ExecutedPeriod {
  StepArray position_steps{};    ///< the drives' whole-step positions at the period's end
  StepArray steps{};             ///< steps in this period (signed)
  ValueArray set_point_steps{};  ///< the continuous set point they were rounded from
  int line = 0;                  ///< program line of the nominal motion at τ
  double factor = 0.0;           ///< K at the period's end
  double tau_periods = 0.0;      ///< nominal time reached, in nominal periods from the program's start
  ExecutionState state = ExecutionState::idle;
};

class StepExecutor {
 public:
  static constexpr int kWindow = 4096;  ///< nominal periods held (plus the one before τ)

  explicit StepExecutor(const ExecutorSettings& settings);

  /// A new program starts from `start_steps` (the drives' positions before its first nominal period).
  void start(const StepArray& start_steps);
  /// Room for another nominal period.
  bool has_room() const noexcept;
  /// Appends a nominal period (call only with has_room()). False when it lies outside the software stops:
  /// the executor then stops before it and reports stopped_at_limit.
  bool push(const NominalPeriod& period) noexcept;
  /// No more nominal periods will come: the last one pushed ends the program.
  void end_of_program() noexcept { stream_ended_ = true; }
  /// One servo period.
  void period(const ExecutionControls& controls, ExecutedPeriod& out) noexcept;

  ExecutionState state() const noexcept { return state_; }
  int fault_line() const noexcept { return fault_line_; }
  /// Nominal periods waiting ahead of τ.
  long periods_ahead() const noexcept;
  /// The nominal periods (τ, in periods) K needs to stop from where it is.
  double stopping_distance_periods() const noexcept;

 private:
  const NominalPeriod& point(long index) const noexcept;
  void interpolate(ExecutedPeriod& out) const noexcept;
  bool inside_stops(const StepArray& position) const noexcept;

  ExecutorSettings settings_;
  OverrideLaw law_;
  std::array<NominalPeriod, kWindow + 2> ring_{};
  long first_ = 0;  ///< oldest point kept (point 0 is the start position)
  long count_ = 0;  ///< points held: first_ … first_ + count_ − 1
  long base_ = 0;   ///< τ = base_ + fraction_, in nominal periods
  double fraction_ = 0.0;
  bool stream_ended_ = false;
  long limit_point_ = -1;  ///< first point outside the stops (−1: none)
  int fault_line_ = 0;
  StepArray released_{};
  ExecutionState state_ = ExecutionState::idle;
};

}  // namespace pkm::execution
