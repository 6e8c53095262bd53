#pragma once
// The loop of the batch calls: independent rows, run in blocks across TBB's threads when there are enough of
// them, serially otherwise. Rows may finish in any order on any thread, yet the failure reported is always
// the lowest row's, so results and errors do not depend on the number of threads.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstddef>
#include <limits>

namespace pkm::python {

/// Rows per TBB task: about 10–100 µs of IK, large against TBB's per-task cost, small enough to balance.
constexpr std::size_t kRowsPerTask = 512;
/// Below this many rows the GIL stays held: releasing and taking it back costs more than the work.
constexpr std::size_t kRowsToReleaseGil = 64;

/// The lowest row index of a kind of failure, shared by the threads of a loop.
class FirstRow {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  void offer(std::size_t row) noexcept {
    std::size_t seen = first_.load(std::memory_order_relaxed);
    while (row < seen && !first_.compare_exchange_weak(seen, row, std::memory_order_relaxed)) {
    }
  }
  std::size_t get() const noexcept { return first_.load(std::memory_order_relaxed); }
  bool any() const noexcept { return get() != kNone; }

 private:
  std::atomic<std::size_t> first_{kNone};
};

/// Calls body(begin, end) for consecutive ranges of rows covering [0, rows): in parallel ranges of about
/// kRowsPerTask rows when there are at least two ranges' worth, else once for all rows. body must only touch
/// its own rows' outputs.
template <class Body>
void for_each_range(std::size_t rows, Body&& body) {
  if (rows < 2 * kRowsPerTask) {
    body(std::size_t{0}, rows);
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, rows, kRowsPerTask),
      [&body](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
}

/// Calls body(row) for every row in [0, rows), as for_each_range distributes them.
template <class Body>
void for_each_row(std::size_t rows, Body&& body) {
  for_each_range(rows, [&body](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row != end; ++row) body(row);
  });
}

}  // namespace pkm::python
