#include "planning/tick_queue.hpp"

namespace pkm::planning {

TickQueue::TickQueue(std::size_t batch_ticks, std::size_t batches)
    : ring_(batches), batch_ticks_(batch_ticks) {
  for (Batch& batch : ring_) batch.ticks.resize(batch_ticks);
}

// The filling batch goes to the consumer; then waits for a free one. False once cancelled.
bool TickQueue::publish() {
  std::unique_lock lock(mutex_);
  if (cancelled_) return false;
  ++produced_;
  changed_.notify_all();
  changed_.wait(lock, [this] { return cancelled_ || produced_ - consumed_ < ring_.size(); });
  return !cancelled_;
}

bool TickQueue::push(const ServoTick& tick) {
  // The batch at produced_ is the producer's alone until it is published.
  Batch& batch = ring_[produced_ % ring_.size()];
  batch.ticks[batch.count++] = tick;
  if (batch.count < batch_ticks_) return true;
  return publish();
}

void TickQueue::close(std::optional<Error> error) {
  std::lock_guard lock(mutex_);
  // The filling batch always has its slot (push waited for it), so its ticks are published, never dropped.
  if (ring_[produced_ % ring_.size()].count > 0) ++produced_;
  error_ = std::move(error);
  closed_ = true;
  changed_.notify_all();
}

bool TickQueue::pop(ServoTick& tick) {
  for (;;) {
    if (reading_) {
      Batch& batch = ring_[consumed_ % ring_.size()];
      if (read_ < batch.count) {
        tick = batch.ticks[read_++];
        return true;
      }
      std::lock_guard lock(mutex_);
      batch.count = 0;
      ++consumed_;
      reading_ = false;
      changed_.notify_all();
    }
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return closed_ || produced_ > consumed_; });
    if (produced_ == consumed_) return false;  // closed, and every batch read
    reading_ = true;
    read_ = 0;
  }
}

void TickQueue::cancel() {
  std::lock_guard lock(mutex_);
  cancelled_ = true;
  changed_.notify_all();
}

}  // namespace pkm::planning
