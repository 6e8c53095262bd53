#pragma once
// A thread that compresses or decompresses a table's chunks while the caller fills or reads the next ones:
// tasks run one at a time in the order they were handed on, on one thread for the table's whole life (a
// thread per chunk made the allocator spread the chunks over new arenas, and the memory grew with the run).
// The caller bounds how many tasks wait (the futures it holds).
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

#include "core/thread_priority.hpp"

namespace pkm::formats {

class ChunkWorker {
 public:
  /// How much lower a filter thread runs than the thread that fills its chunks: on two cores, measured best
  /// with the tick-making thread 5 lower (docs/PERFORMANCE.md).
  static constexpr int kFilterNiceSteps = 10;
  ChunkWorker() : thread_([this] { serve(); }) {}
  ~ChunkWorker() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  ChunkWorker(const ChunkWorker&) = delete;
  ChunkWorker& operator=(const ChunkWorker&) = delete;

  /// Runs `work` on the thread; the future ends with it (or its exception).
  std::future<void> submit(std::function<void()> work) {
    std::packaged_task<void()> task(std::move(work));
    std::future<void> result = task.get_future();
    {
      std::lock_guard lock(mutex_);
      tasks_.push_back(std::move(task));
    }
    wake_.notify_one();
    return result;
  }

 private:
  void serve() {
    // The table's filling thread is the run's longest; its chunks can wait (three may be in flight).
    lower_this_thread_priority(kFilterNiceSteps);
    for (;;) {
      std::packaged_task<void()> task;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
        if (tasks_.empty()) return;
        task = std::move(tasks_.front());
        tasks_.pop_front();
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<void()>> tasks_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace pkm::formats
