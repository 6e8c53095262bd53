#pragma once
// A thread that does work the run can wait for (deflating a chunk, making ticks ahead of their use) yields
// its core to the thread the run waits on. On two cores a run has four threads, and the scheduler shares the
// cores among them evenly unless told which matter: the run's longest thread then waits for a core while
// work that could have been done later runs (docs/PERFORMANCE.md, "Less work per tick").
namespace pkm {

/// Lowers the calling thread's scheduling priority by `nice_steps` (Linux per-thread nice; no privilege
/// needed to lower it). Elsewhere, and where the system refuses, nothing changes.
void lower_this_thread_priority(int nice_steps);

}  // namespace pkm
