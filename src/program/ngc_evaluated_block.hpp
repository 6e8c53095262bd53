#pragma once
// What the RS274/NGC front end hands the block executor: one block whose parameters, expressions and O-word
// control flow have been resolved. Every word carries a plain number and the column it was written at; the
// block knows the file and line it came from and, inside a subroutine, the line of the main program that
// called it, so that every canonical move and every error can point at the program text.
#include <string>
#include <vector>

#include "program/gcode_lexer.hpp"

namespace pkm::program::ngc {

/// Where a block is. `file` indexes BlockReader::files() (0 = the main program); `line` is the line in that
/// file; `call_line` is the line of the main program that is running (the outermost O-word call, or `line`
/// itself when the block is in the main program's own flow).
struct SourceRef {
  int file = 0;
  int line = 0;
  int call_line = 0;
};

/// A comment that LinuxCNC acts on: (MSG,…) shows text, (DEBUG,…) shows text with parameter values
/// substituted, (PRINT,…) prints it to stderr.
enum class MessageKind { msg, debug, print };
struct Message {
  MessageKind kind = MessageKind::msg;
  std::string text;  ///< parameters already substituted (DEBUG and PRINT), as LinuxCNC prints them
  int column = 0;
};

struct EvaluatedBlock {
  SourceRef where;
  bool block_delete = false;  ///< written with a leading '/' (the reader skips it when block delete is on)
  std::vector<gcode::Word> words;  ///< in the order written, without N and O words; values in program units
  std::vector<Message> messages;
  void clear() {
    block_delete = false;
    words.clear();
    messages.clear();
  }
};

}  // namespace pkm::program::ngc
