// A worker thread lowers its own priority only (src/core/thread_priority.hpp): the thread that made it keeps
// its own.
#include "core/thread_priority.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <thread>

namespace pkm {
namespace {

int this_thread_nice() {
  return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

TEST(ThreadPriority, AThreadLowersItsOwnPriorityAndNoOneElses) {
  const int before = this_thread_nice();
  int worker_before = 0, worker_after = 0;
  std::thread worker([&] {
    worker_before = this_thread_nice();
    lower_this_thread_priority(3);
    worker_after = this_thread_nice();
  });
  worker.join();
  EXPECT_EQ(worker_before, before);  // a new thread starts at its maker's
  EXPECT_EQ(worker_after, std::min(worker_before + 3, 19));
  EXPECT_EQ(this_thread_nice(), before);
}

}  // namespace
}  // namespace pkm
