#pragma once
// A part program read on a thread of its own while the planner takes its moves: the reader hands the moves
// over in batches through a bounded queue, so neither the program's moves nor the reader's lead grow with
// the program, and reading overlaps planning on a second core. The reader's error reaches the planner at the
// place in the moves where it stopped; a planner that gives up stops the reader at its next move.
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "io/mapped_text.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "planning/move_source.hpp"
#include "planning/plan_producer.hpp"

namespace pkm::pipeline {

/// Where the moves of each main-program line were written when that is elsewhere (subroutine_lines), move by
/// move.
class SubroutineLines {
 public:
  void add(const program::CanonicalMove& move);
  /// The JSON of subroutine_lines, naming the files of `files` (the program's).
  nlohmann::json json(const std::vector<std::string>& files) const;

 private:
  std::map<int, std::vector<std::pair<int, int>>> places_;  ///< line → (file, line) in order
};

class ProgramStream final : public planning::MoveSource {
 public:
  /// Starts reading `program_path` for `machine`. `places`, when given, is told every move; `header`, when
  /// given, gets the program without its moves (format, files, notes) once it is read.
  ProgramStream(const Machine& machine, std::string program_path, ProgramOptions options,
                SubroutineLines* places = nullptr, program::CanonicalProgram* header = nullptr);
  ~ProgramStream() override;

  Result<const program::CanonicalMove*> next() override;
  int line_count() const override { return line_count_; }
  Result<program::CanonicalProgram> whole() const override;

 private:
  Status take(const program::CanonicalMove& move);
  void read();
  void stop();

  const Machine& machine_;
  std::string path_;
  ProgramOptions options_;
  SubroutineLines* places_;
  int line_count_ = 0;
  program::CanonicalProgram* header_;
  std::unique_ptr<MappedText> text_;  ///< the file, given back behind the reader
  std::optional<Error> open_error_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::vector<program::CanonicalMove>> full_;  ///< batches read, not yet planned
  std::vector<program::CanonicalMove> filling_;           ///< the reader's batch
  std::vector<program::CanonicalMove> taking_;            ///< the planner's batch
  std::size_t taken_ = 0;
  bool done_ = false;       ///< the reader ended (result_ says how)
  bool cancelled_ = false;  ///< the planner gave up
  std::optional<Error> error_;
  std::thread reader_;
};

/// A plan made while its program is read on a thread of its own (ProgramStream), its memory bounded by the
/// planner's window. The members are on the heap where the plan's source reads and writes them; `plan` is
/// last, so its reader stops before what it writes goes.
struct StreamedProgramPlan {
  std::unique_ptr<program::CanonicalProgram> program;  ///< the file's name and start, without its moves
  std::unique_ptr<SubroutineLines> places;             ///< where the reader found each move
  std::unique_ptr<program::CanonicalProgram> header;   ///< format, files, notes: whole once the plan is
  std::unique_ptr<planning::StreamedPlan> plan;
};
Result<StreamedProgramPlan> start_streamed_program_plan(const Machine& machine,
                                                        const std::string& program_path,
                                                        const ProgramOptions& program_options,
                                                        const planning::PlanOptions& options);

}  // namespace pkm::pipeline
