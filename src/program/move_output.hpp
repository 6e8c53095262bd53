#pragma once
// Where a reader's canonical moves go: into the program's list, or one by one to a sink (a planner that reads
// while the program is read, so the moves of a long program are never all held). The sink gets each move one
// move late: until the next move comes, the reader may still mark the last one as an exact stop (M0, M1).
#include <cstddef>
#include <functional>
#include <optional>

#include "core/result.hpp"
#include "program/canonical_program.hpp"

namespace pkm::program {

/// Takes the moves in order; an error stops the reading with it (the reader's caller gave up).
using MoveSink = std::function<Status(const CanonicalMove&)>;

class MoveOutput {
 public:
  /// Into `program.moves`, or with a `sink` to it.
  void attach(CanonicalProgram& program, MoveSink sink);
  Status push(const CanonicalMove& move);
  /// The move pushed last, still open to change; null before the first.
  CanonicalMove* last();
  std::size_t count() const { return count_; }
  /// The sink's error, once it failed (the reader stops at its next statement).
  const Status& status() const { return status_; }
  /// The reading ended: the move held back goes to the sink.
  Status flush();

 private:
  CanonicalProgram* program_ = nullptr;
  MoveSink sink_;
  std::optional<CanonicalMove> held_;
  std::size_t count_ = 0;
  Status status_ = ok_status();
};

}  // namespace pkm::program
