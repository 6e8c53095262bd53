#include "core/thread_priority.hpp"

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace pkm {

void lower_this_thread_priority(int nice_steps) {
#if defined(__linux__)
  // On Linux a thread's nice value is its own: PRIO_PROCESS with the thread's id sets only this thread's.
  const auto thread = static_cast<id_t>(gettid());
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, thread);
  if (errno == 0) setpriority(PRIO_PROCESS, thread, current + nice_steps);  // a refusal changes nothing
#else
  (void)nice_steps;
#endif
}

}  // namespace pkm
