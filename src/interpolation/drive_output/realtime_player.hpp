#pragma once
// Releasing drive steps at the servo rate, as a controller's real-time loop would hand them to the drives
// (Smirnov 2019, §5.1: with code control a period's increment is sent at the period's start; §5.2.2: the
// values for period i must be ready before it starts). The player sleeps to absolute CLOCK_MONOTONIC
// deadlines t0 + k·h with clock_nanosleep(TIMER_ABSTIME), so that a late wake-up delays one period and never
// shifts the ones after it, hands period k to a sink as soon as it wakes, and measures its own lateness
// (wake-up time − deadline, never negative: the clock does not wake early).
//
// A period whose lateness exceeds h is an overrun; the player does not skip it but releases it at once and
// keeps the original deadlines, so it catches up. Reading the file is kept out of the timed part: periods are
// decoded ahead into a fixed ring before t0 and topped up right after each release, in the time left until
// the next deadline. The per-period path does not allocate (the sink's write() aside).
//
// During a run the thread's timer slack is set to 1 ns (an ordinary thread's timers may otherwise fire up to
// 50 µs late). Optionally (try_realtime) the player locks its memory (mlockall) and asks for SCHED_FIFO; both
// need privileges an ordinary user or a container usually lacks, and a refusal is reported, not an error.
// All of it is undone afterwards.
#include <cstdint>

#include "core/duration_histogram.hpp"
#include "core/result.hpp"
#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/quantisation/step_period.hpp"

namespace pkm::interpolation {

struct PlayerSettings {
  double period_s = 0.0;      ///< servo period h; 0: the stream's own
  long max_periods = -1;      ///< stop after this many periods; negative: play them all
  bool try_realtime = false;  ///< try mlockall and SCHED_FIFO
};

struct PlayerStatistics {
  long periods = 0;  ///< released
  /// Wake-up time − deadline of every period, in a fixed histogram (core/duration_histogram.hpp: within 3 %,
  /// no memory per period); over_budget counts the overruns.
  DurationDistribution lateness;
  double max_lateness_us = 0.0, mean_lateness_us = 0.0, p99_lateness_us = 0.0;  ///< as in `lateness`
  double min_lateness_us = 0.0;  ///< ≥ 0 unless the clock woke early
  long overruns = 0;             ///< periods released more than h after their deadline
  bool memory_locked = false;
  bool realtime_priority = false;
  double wall_time_s = 0.0;  ///< from t0 (the first deadline) to the end of the last release
  /// t0 on CLOCK_MONOTONIC (ns): period k is due at t0 + k·h, so a sink can check it was never fed early.
  std::int64_t first_deadline_ns = 0;
};

/// Plays `source` from its current position into `sink`, one period every h, then finishes the sink. On an
/// error (a decoding error of the source, a failing sink) it stops at once and does not finish the sink.
Result<PlayerStatistics> play(StepStreamReader& source, StepSink& sink, const PlayerSettings& settings);

}  // namespace pkm::interpolation
