#pragma once
// The interpolator's output: whole steps per servo period (Smirnov 2019, §5.1 "constant carrier frequency",
// §5.2.2). Each period gives every actuator a signed step count — under pulse control that many pulses spread
// over the period, the sign selecting the direction; under code control the increment of the position code —
// and the resulting integer position code. Sinks (steps_csv.hpp, step_stream.hpp, realtime_player.hpp) take
// the periods one at a time so that a run of any length needs no memory per period.
#include <array>
#include <cstdint>
#include <string>

#include "core/result.hpp"
#include "machine/mechanism.hpp"

namespace pkm::interpolation {

struct StepPeriod {
  long index = 0;                                      ///< period number, from 0
  double time_s = 0.0;                                 ///< real time at the end of the period
  int line = 0;                                        ///< program line at the end of the period
  std::array<std::int32_t, kMaxActuators> steps{};     ///< signed steps in this period (sign = direction)
  std::array<std::int64_t, kMaxActuators> position{};  ///< position code at the end of the period, in steps
  /// The ideal (continuous) actuator values the whole steps stand for at the period's end, in steps: what an
  /// executor interpolates between when it scales time (execution/step_executor.hpp). The estimating
  /// method, which has no continuous law, gives its positions.
  std::array<double, kMaxActuators> ideal_steps{};
};

struct StepStreamHeader {
  int actuators = 6;
  double period_s = 0.001;
  double step_mm = 0.001;  ///< mm per step (rad per step for angular actuators)
  std::array<std::int64_t, kMaxActuators> start_position{};  ///< position codes before the first period
  std::string machine;                                       ///< machine file name, for the record
};

/// Where periods go: files, the player, tests. write() is called once per period in order, finish() once
/// after the last one; a sink that is destroyed without a successful finish() leaves no output file behind.
class StepSink {
 public:
  virtual ~StepSink() = default;
  virtual Status write(const StepPeriod& period) = 0;
  virtual Status finish() = 0;
};

}  // namespace pkm::interpolation
