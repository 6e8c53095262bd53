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

bool TickQueue::commit() {
  // The batch at produced_ is the producer's alone until it is published.
  if (++filling_ < batch_ticks_) return true;
  ring_[produced_ % ring_.size()].count = filling_;
  filling_ = 0;
  return publish();
}

bool TickQueue::push(const ServoTick& tick) {
  slot() = tick;
  return commit();
}

void TickQueue::close(std::optional<Error> error) {
  std::lock_guard lock(mutex_);
  // The filling batch always has its slot (commit waited for it), so its ticks are published, never dropped.
  if (filling_ > 0) {
    ring_[produced_ % ring_.size()].count = filling_;
    filling_ = 0;
    ++produced_;
  }
  error_ = std::move(error);
  closed_ = true;
  changed_.notify_all();
}

bool TickQueue::pop(ServoTick& tick) {
  const ServoTick* next_tick = next();
  if (next_tick == nullptr) return false;
  tick = *next_tick;
  return true;
}

const ServoTick* TickQueue::next() {
  for (;;) {
    if (reading_) {
      Batch& batch = ring_[consumed_ % ring_.size()];
      if (read_ < batch.count) return &batch.ticks[read_++];
      std::lock_guard lock(mutex_);
      batch.count = 0;
      ++consumed_;
      reading_ = false;
      changed_.notify_all();
    }
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return closed_ || produced_ > consumed_; });
    if (produced_ == consumed_) return nullptr;  // closed, and every batch read
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
