#pragma once
// Splits one line of RS274/NGC into words (letter + number), each with the column it was written at, so that
// every later error can point at the offending word. Syntax accepted (as LinuxCNC reads it):
//  - letters in either case; blanks anywhere between a letter and its number and inside the number
//    ("g 1 x 1 0 . 5" is G1 X10.5); numbers are [+|-]digits[.digits], no exponent;
//  - comments `( ... )` (not nested, closed on the same line) and `;` to the end of the line;
//  - `/` as the first non-blank character marks a block-delete block; an `N` word may open the block;
//  - a line holding only `%` is a program-start/end marker.
// Parameters (#), expressions ([...]) and O-words are rejected here, with their column. The lexer does not
// allocate once its word buffer has grown to the longest block.
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm::program::gcode {

/// Where a line is, for messages: "SOURCE:LINE:COL: message".
struct LineRef {
  const std::string& source;
  int line = 0;  ///< 1-based
};

/// An error at a column of a line, code bad_input.
Error error_at(const LineRef& where, int column, std::string_view message);

struct Word {
  char letter = 0;     ///< upper case
  double value = 0.0;  ///< the number as written
  int column = 0;      ///< 1-based column of the letter
};

struct LexedLine {
  bool block_delete = false;  ///< the block starts with '/'
  bool percent = false;       ///< the line is a '%' marker
  std::vector<Word> words;    ///< in the order written, without the N word
  bool empty() const { return words.empty(); }
};

/// Lexes `text` (one line, without its newline) into `out` (cleared first).
Status lex_line(std::string_view text, const LineRef& where, LexedLine& out);

}  // namespace pkm::program::gcode
