#pragma once
// The RS274/NGC front end: reads a program's lines, evaluates parameters and expressions, carries out O-word
// control flow (sub/endsub/call/return, if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat,
// break/continue; subroutine files on the subroutine path) and parameter assignments, and yields the blocks
// to execute one at a time. The executor (gcode_interpreter.cpp) gives them their meaning.
//
// Contract (implemented in ngc_block_reader.cpp):
//   - next() fills `out` with the next block to execute and returns true; false at the end of the main
//     program's text or at a '%' line that ends it (a '%' before the first block opens the program). Empty
//     lines, comment-only lines (other than MSG/DEBUG/PRINT) and O-word lines are consumed internally.
//   - Parameter assignments on a line take effect after every word of the line has been evaluated (LinuxCNC:
//     `#1=2 #2=#1` sets #2 to the old #1), and before next() returns the block.
//   - Errors carry file:line:column (of the file the line is in) and code bad_input; a program that executes
//     more than max_blocks blocks, or calls deeper than max_call_depth, is refused at the line that crossed
//     the bound.
//   - The executor stops calling next() after M2/M30; M99 and Fanuc-style subprograms are not part of this.
//   - No allocation per block once the buffers have grown (the block, the expression stack, the loop stack).
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/ngc_evaluated_block.hpp"
#include "program/ngc_parameters.hpp"

namespace pkm::program::ngc {

struct ReaderOptions {
  /// Folders searched, in order, for `O<name> call` of a subroutine not defined in the program: the file
  /// `<name>.ngc` (name in lower case) holding `O<name> sub … O<name> endsub` (LinuxCNC SUBROUTINE_PATH).
  std::vector<std::string> subroutine_path;
  bool block_delete = true;                ///< skip blocks written with a leading '/'
  std::uint64_t max_blocks = 100'000'000;  ///< executed blocks (loop bodies count every time)
  int max_call_depth = 100;                ///< nested O-word calls
};

class BlockReader {
 public:
  /// `text` must outlive the reader; `parameters` and `predefined` are the executor's.
  BlockReader(std::string_view text, std::string source_name, const ReaderOptions& options,
              ParameterStore& parameters, const PredefinedParameters& predefined);
  ~BlockReader();
  BlockReader(const BlockReader&) = delete;
  BlockReader& operator=(const BlockReader&) = delete;

  Result<bool> next(EvaluatedBlock& out);

  /// Names of the files read so far: [0] the main program, then subroutine files in the order opened.
  const std::vector<std::string>& files() const;
  /// The line the reader stopped at in the main program (for CanonicalProgram::end_line).
  int main_line() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::program::ngc
