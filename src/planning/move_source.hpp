#pragma once
// The canonical moves a plan is made of, in order: from a program read whole, or from a reader still reading
// it (pipeline/program_stream.hpp), so that a planner never needs all of a long program at once.
#include <functional>
#include <memory>

#include "core/result.hpp"
#include "program/canonical_program.hpp"

namespace pkm::planning {

class MoveSource {
 public:
  virtual ~MoveSource() = default;
  /// The next move, valid until the next call; null after the last. The reader's errors name their line.
  virtual Result<const program::CanonicalMove*> next() = 0;
  /// The program's lines, for the progress' fraction (0: unknown).
  virtual int line_count() const = 0;
  /// The whole program again, for the reports that need all of it (where a program leaves the workspace).
  virtual Result<program::CanonicalProgram> whole() const = 0;
};

/// The moves of a program read whole.
class ProgramMoves final : public MoveSource {
 public:
  explicit ProgramMoves(const program::CanonicalProgram& program) : program_(program) {}
  Result<const program::CanonicalMove*> next() override {
    if (next_ >= program_.moves.size()) return static_cast<const program::CanonicalMove*>(nullptr);
    return &program_.moves[next_++];
  }
  int line_count() const override { return program_.end_line; }
  Result<program::CanonicalProgram> whole() const override { return program_; }

 private:
  const program::CanonicalProgram& program_;
  std::size_t next_ = 0;
};

/// Makes a fresh source for each pass over the program.
using MoveSourceFactory = std::function<Result<std::unique_ptr<MoveSource>>()>;

}  // namespace pkm::planning
