#pragma once
// One line of RS274/NGC, read as LinuxCNC 2.9 reads it (blanks ignored and letters case-insensitive outside
// comments): a leading '/' (block delete), an optional N word, then either an O-word statement or words
// (letter + real value) and parameter assignments (`#n=…`, `#<name>=…`) in the order written, and comments.
// Only the last `( )` comment of a line counts, as in LinuxCNC; (MSG,…), (DEBUG,…), (PRINT,…) and (ABORT,…)
// are recognised case-insensitively after leading blanks.
//
// Expressions are parsed, not evaluated: the reader evaluates them, because an O-word line's expressions are
// only evaluated when the line is not being skipped. An O-word line is parsed in two steps for the same
// reason: the head (number or <name>, and keyword), then the tail (its bracketed expressions), which LinuxCNC
// does not even read on lines it skips. All buffers keep their capacity from line to line.
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/gcode_lexer.hpp"
#include "program/ngc_expression.hpp"

namespace pkm::program::ngc {

enum class OKeyword : unsigned char {
  none,  ///< a bare program number (`O0001`), which rs274 ignores
  sub,
  endsub,
  call,
  do_,
  while_,
  repeat,
  if_,
  elseif,
  else_,
  endif,
  break_,
  continue_,
  endwhile,
  endrepeat,
  return_,
};
const char* to_string(OKeyword keyword);

enum class ItemKind : unsigned char { word, set_number, set_named };

/// A word or an assignment, in the order written.
struct LineItem {
  ItemKind kind = ItemKind::word;
  char letter = 0;        ///< words: upper case
  int column = 0;         ///< of the letter or the '#'
  bool constant = false;  ///< the value is a plain number (`value`), no code to run
  double value = 0.0;
  ExpressionRef expression;      ///< the value's code when not constant
  ExpressionRef target;          ///< set_number: the code giving the parameter number
  std::uint32_t name_begin = 0;  ///< set_named: the name in ExpressionCode::names
  std::uint32_t name_size = 0;
};

enum class CommentKind : unsigned char { none, plain, msg, debug, print, abort };

struct OWordHead {
  bool named = false;    ///< written O<name>
  std::string name;      ///< the name (normalised) when named
  ExpressionRef number;  ///< the number's code when not named
  int column = 0;        ///< of the O
  OKeyword keyword = OKeyword::none;
  int keyword_column = 0;
  std::size_t after = 0;  ///< where the tail starts in the normalised line
};

struct ParsedLine {
  bool block_delete = false;
  bool percent = false;  ///< the line is a lone '%'
  bool is_o_word = false;
  OWordHead o;
  std::vector<ExpressionRef> o_arguments;  ///< call arguments; the condition; the returned value
  std::vector<LineItem> items;
  CommentKind comment = CommentKind::none;  ///< of the last ( ) comment
  std::string_view comment_text;            ///< after "MSG," / "DEBUG," … (view into the raw line)
  int comment_column = 0;
  ExpressionCode code;
};

/// Parses everything of `raw` except an O-word's tail. `line` is the normalised text (kept for parse_o_tail).
/// With `o_word_only` (a line read while skipping) the words of a line that is not an O-word line are not
/// parsed: LinuxCNC does not read them either, so errors in them do not count.
Status parse_line(std::string_view raw, const gcode::LineRef& where, NormalizedLine& line, ParsedLine& out,
                  bool o_word_only = false);
/// The fast path for the lines CAM output is made of (`N10 G1 X12.345 Y-3.2 F1200`): letters, digits, points,
/// signs and blanks only. Fills `words` and returns true when the line is such a line and well formed; false
/// (with `words` in any state) for anything else, which the full parser then reads and judges.
bool lex_simple_line(std::string_view raw, std::vector<gcode::Word>& words);

/// Parses the bracketed expressions after an O-word's keyword into out.o_arguments, then checks that only
/// comments follow ("Unexpected character after O-word"); up to 30 call arguments.
Status parse_o_tail(const NormalizedLine& line, const gcode::LineRef& where, ParsedLine& out);

/// What (DEBUG,…), (PRINT,…) and (ABORT,…) show: `#n` and `#<name>` replaced by their values with LinuxCNC's
/// formats (six decimals, or as set by %d, %f, %.Nf before them); "######" for unknown ones.
/// `store` answers #1 … #5601 (#0 shows 0); `names` answers names (nullopt: unknown).
Status expand_parameters_in_comment(std::string_view text, const ParameterStore& store,
                                    const NamedParameterSource& names, const gcode::LineRef& where,
                                    int column, std::string& out);

}  // namespace pkm::program::ngc
