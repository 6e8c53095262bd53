#include "interpolation/drive_output/realtime_player.hpp"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>

namespace pkm::interpolation {

namespace {

constexpr std::int64_t kPlayerNsPerS = 1'000'000'000;
// Decoded periods kept ahead of the deadline: at 10 kHz, a tenth of a second.
constexpr std::size_t kPlayerReadAhead = 1024;
// Periods decoded after each release: more than the one consumed, so the ring refills after a slow read.
constexpr int kPlayerRefillPerPeriod = 4;
// SCHED_FIFO priority when granted: above ordinary real-time helpers, below the kernel's own (≥ 90).
constexpr int kPlayerFifoPriority = 80;

std::int64_t player_now_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * kPlayerNsPerS + now.tv_nsec;
}

void player_sleep_until(std::int64_t deadline_ns) {
  timespec deadline{};
  deadline.tv_sec = static_cast<time_t>(deadline_ns / kPlayerNsPerS);
  deadline.tv_nsec = static_cast<long>(deadline_ns % kPlayerNsPerS);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

// For the duration of a run, undone by the destructor: the smallest timer slack (Linux lets an ordinary
// thread's timers fire up to 50 µs late by default, to batch wake-ups; that would be half a period at 10
// kHz), and when asked for, mlockall and SCHED_FIFO.
class PlayerRealtime {
 public:
  explicit PlayerRealtime(bool wanted) {
    const int slack = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
    if (slack > 1 && prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0) == 0) old_slack_ns_ = slack;
    if (!wanted) return;
    locked_ = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
    if (pthread_getschedparam(pthread_self(), &old_policy_, &old_param_) != 0) return;
    sched_param fifo{};
    fifo.sched_priority = std::min(kPlayerFifoPriority, sched_get_priority_max(SCHED_FIFO));
    fifo_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &fifo) == 0;
  }
  ~PlayerRealtime() {
    if (fifo_) pthread_setschedparam(pthread_self(), old_policy_, &old_param_);
    if (locked_) munlockall();
    if (old_slack_ns_ > 0) prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(old_slack_ns_), 0, 0, 0);
  }
  PlayerRealtime(const PlayerRealtime&) = delete;
  PlayerRealtime& operator=(const PlayerRealtime&) = delete;

  bool locked() const { return locked_; }
  bool fifo() const { return fifo_; }

 private:
  bool locked_ = false;
  bool fifo_ = false;
  int old_slack_ns_ = 0;
  int old_policy_ = SCHED_OTHER;
  sched_param old_param_{};
};

// Periods decoded ahead of their deadline, in a ring allocated once.
class PlayerReadAhead {
 public:
  explicit PlayerReadAhead(StepStreamReader& source) : source_(source), ring_(kPlayerReadAhead) {}
  /// Decodes up to `most` more periods while there is room.
  void refill(std::size_t most) {
    for (; most > 0 && size_ < ring_.size() && !exhausted_; --most) {
      if (!source_.next(ring_[(head_ + size_) % ring_.size()])) {
        exhausted_ = true;
        return;
      }
      ++size_;
    }
  }
  bool empty() const { return size_ == 0; }
  const StepPeriod& front() const { return ring_[head_]; }
  void pop() {
    head_ = (head_ + 1) % ring_.size();
    --size_;
  }

 private:
  StepStreamReader& source_;
  std::vector<StepPeriod> ring_;
  std::size_t head_ = 0, size_ = 0;
  bool exhausted_ = false;
};

}  // namespace

Result<PlayerStatistics> play(StepStreamReader& source, StepSink& sink, const PlayerSettings& settings) {
  if (!std::isfinite(settings.period_s) || settings.period_s < 0.0)
    return make_error(ErrorCode::bad_input, fmt::format("servo period {} s", settings.period_s));
  const std::int64_t period_ns = settings.period_s > 0.0
                                     ? static_cast<std::int64_t>(std::llround(settings.period_s * 1e9))
                                     : source.period_ns();
  if (period_ns < 1)
    return make_error(ErrorCode::bad_input,
                      fmt::format("servo period {} s is below 1 ns", settings.period_s));
  const long limit = settings.max_periods >= 0 ? settings.max_periods : std::numeric_limits<long>::max();

  PlayerReadAhead ahead(source);
  ahead.refill(kPlayerReadAhead);
  if (source.error()) return *source.error();
  DurationHistogram lateness(period_ns);
  PlayerStatistics statistics;
  PlayerRealtime realtime(settings.try_realtime);
  statistics.memory_locked = realtime.locked();
  statistics.realtime_priority = realtime.fifo();

  // The first deadline one period ahead, so that setting up is not counted as lateness of period 0.
  const std::int64_t t0 = player_now_ns() + period_ns;
  long released = 0;
  for (; released < limit; ++released) {
    if (ahead.empty()) {
      ahead.refill(kPlayerReadAhead);  // only at the end of the stream: the ring is kept full otherwise
      if (ahead.empty()) break;
    }
    const std::int64_t deadline = t0 + released * period_ns;
    player_sleep_until(deadline);
    const std::int64_t late = player_now_ns() - deadline;
    lateness.add(late);
    if (late > period_ns) ++statistics.overruns;
    if (auto written = sink.write(ahead.front()); !written) return written.error();
    ahead.pop();
    ahead.refill(kPlayerRefillPerPeriod);
    if (source.error()) return *source.error();
  }
  const std::int64_t end = player_now_ns();
  statistics.periods = released;
  statistics.first_deadline_ns = t0;
  statistics.wall_time_s = released ? static_cast<double>(end - t0) * 1e-9 : 0.0;
  statistics.max_lateness_us = lateness.max_us();
  statistics.min_lateness_us = lateness.min_us();
  statistics.mean_lateness_us = lateness.mean_us();
  statistics.lateness = lateness.distribution();
  statistics.p99_lateness_us = statistics.lateness.p99_us;
  if (auto finished = sink.finish(); !finished) return finished.error();
  return statistics;
}

}  // namespace pkm::interpolation
