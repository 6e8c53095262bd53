#pragma once
// Releasing drive steps at the servo rate, as a controller's real-time loop would hand them to the drives
// (spec ch5 §2: with code control each period's increment is sent at the start of the period; §5.5: the
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
#include <vector>

#include "core/result.hpp"
#include "interpolation/step_period.hpp"
#include "interpolation/step_stream.hpp"

namespace pkm::interpolation {

struct PlayerSettings {
  double period_s = 0.0;      ///< servo period h; 0: the stream's own
  long max_periods = -1;      ///< stop after this many periods; negative: play them all
  bool try_realtime = false;  ///< try mlockall and SCHED_FIFO
};

struct PlayerStatistics {
  long periods = 0;  ///< released
  double max_lateness_us = 0.0, mean_lateness_us = 0.0, p99_lateness_us = 0.0;
  double min_lateness_us = 0.0;  ///< ≥ 0 unless the clock woke early
  long overruns = 0;             ///< periods released more than h after their deadline
  bool memory_locked = false;
  bool realtime_priority = false;
  double wall_time_s = 0.0;  ///< from t0 (the first deadline) to the end of the last release
};

/// Lateness counts in a fixed histogram of 1 µs buckets up to 20 ms (one more for anything later), so that
/// the 99th percentile needs no memory per period. Percentiles are the upper edge of their bucket (at most
/// the largest lateness seen): resolution 1 µs.
class LatenessRecorder {
 public:
  LatenessRecorder();
  void add(std::int64_t lateness_ns);
  long count() const { return count_; }
  double max_us() const { return count_ ? static_cast<double>(max_ns_) * 1e-3 : 0.0; }
  double min_us() const { return count_ ? static_cast<double>(min_ns_) * 1e-3 : 0.0; }
  double mean_us() const { return count_ ? sum_ns_ / static_cast<double>(count_) * 1e-3 : 0.0; }
  /// The lateness that `fraction` (0…1) of the periods did not exceed, µs.
  double percentile_us(double fraction) const;

 private:
  std::vector<std::uint32_t> buckets_;
  long count_ = 0;
  double sum_ns_ = 0.0;
  std::int64_t max_ns_ = 0, min_ns_ = 0;
};

/// Plays `source` from its current position into `sink`, one period every h, then finishes the sink. On an
/// error (a decoding error of the source, a failing sink) it stops at once and does not finish the sink.
Result<PlayerStatistics> play(StepStreamReader& source, StepSink& sink, const PlayerSettings& settings);

}  // namespace pkm::interpolation
