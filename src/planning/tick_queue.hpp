#pragma once
// The servo ticks handed from the thread that makes them (the planner and the stream: path, inverse
// kinematics) to the thread that measures and writes them (the run monitor's forward kinematics, the checks,
// the observers), so that a long run uses both cores. A ring of batches, made once: the lock is taken once
// per batch, nothing is allocated per tick, and a tick is made and read where it lies in its batch (a tick is
// a few hundred bytes, not worth copying in and out at every period). One producer, one consumer.
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

#include "core/result.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::planning {

class TickQueue {
 public:
  explicit TickQueue(std::size_t batch_ticks = 256, std::size_t batches = 8);

  /// The producer's side: the place to make the next tick in, then commit() it. commit() is false once the
  /// consumer has given up (stop producing).
  ServoTick& slot() { return ring_[produced_ % ring_.size()].ticks[filling_]; }
  bool commit();
  /// slot() = tick, commit().
  bool push(const ServoTick& tick);
  /// The producer's last word: the ticks pushed so far are all there are, and `error` (if any) is why.
  void close(std::optional<Error> error);

  /// The consumer's side: the next tick, valid until the next call, or null after the last (then error()
  /// says whether it failed).
  const ServoTick* next();
  /// A copy of next(): false after the last.
  bool pop(ServoTick& tick);
  /// The consumer gives up: the producer's next push returns false.
  void cancel();
  const std::optional<Error>& error() const { return error_; }

 private:
  struct Batch {
    std::vector<ServoTick> ticks;
    std::size_t count = 0;
  };
  bool publish();

  std::vector<Batch> ring_;
  std::size_t batch_ticks_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t produced_ = 0;  ///< batches published (under the lock)
  std::size_t filling_ = 0;   ///< ticks made in the batch at produced_ (the producer's own)
  std::size_t consumed_ = 0;  ///< batches the consumer has finished with (under the lock)
  bool closed_ = false, cancelled_ = false;
  std::optional<Error> error_;  ///< set before closed_, read after it
  // The consumer's place, its own: the batch it reads (valid while reading) and the next tick in it.
  bool reading_ = false;
  std::size_t read_ = 0;
};

}  // namespace pkm::planning
