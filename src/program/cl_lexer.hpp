#pragma once
// Splits APT CL data into statements. The syntax (as NX, Catia and Mastercam write it):
//  - one statement per line, `WORD/arg,arg,...` or a bare `WORD` (RAPID, END, END-OF-PATH);
//  - a `$` as the last non-blank character continues the statement on the next line;
//  - `$$` starts a comment that runs to the end of the line; a line that is only a comment is returned as a
//    comment statement (kept as an event), and `$$-> WORD/…` (Pro/CLfile) as a statement marked annotation;
//  - text statements (PARTNO, PPRINT, INSERT, TPRINT) take the rest of the statement verbatim, commas and
//  all;
//  - major words may contain a blank (`TOOL PATH/...`); case does not matter.
// Every statement and every argument keeps the line and column it was written at, across continuations,
// so that errors point at the offending value.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pkm::program {

/// 'a'…'z' to upper case, anything else unchanged (CL words are ASCII; no locale).
inline char ascii_upper(char c) {
  return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
}

struct ClPosition {
  int line = 0;    ///< 1-based
  int column = 0;  ///< 1-based, in bytes
};

struct ClArg {
  std::string_view text;  ///< trimmed; empty for a missing value (`1,,3`)
  ClPosition at;
};

struct ClStatement {
  std::string word;  ///< major word in upper case, inner blanks collapsed: "GOTO", "TOOL PATH"
  ClPosition at;     ///< first character of the word
  bool has_slash = false;
  bool is_text = false;        ///< a text statement: `text` holds its argument, `args` is empty
  bool is_comment = false;     ///< a whole-line `$$ comment`: `text` holds it, `word` is empty
  bool is_annotation = false;  ///< written as `$$-> WORD/…` (Pro/CLfile's statements for the post-processor)
  std::string_view text;       ///< everything after the '/' (text statements: after the word), trimmed
  ClPosition text_at;          ///< first character of `text`
  std::vector<ClArg> args;     ///< comma-separated values after '/', trimmed
};

class ClLexer {
 public:
  explicit ClLexer(std::string_view text) : text_(text) {}

  /// Reads the next statement into `out`, skipping blank and comment lines; false at the end of the text.
  /// The views in `out` stay valid until the next call.
  bool next(ClStatement& out);

  /// Number of lines in the text (a last line without a newline counts).
  int line_count() const;

 private:
  struct Segment {  // a piece of a continued statement: where it starts in the statement and in the file
    std::size_t offset;
    int line;
    int column;
  };
  /// Collects the physical lines of the next statement into statement_ (and segments_); false at the end.
  bool gather();
  void split(ClStatement& out) const;
  ClPosition position_of(const char* p) const;

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::string_view statement_;  // into text_ (one line) or buffer_ (continued)
  std::string buffer_;
  std::vector<Segment> segments_;
  std::string_view comment_;  // a whole-line comment's text (comment_at_.line > 0)
  ClPosition comment_at_;
  bool annotation_ = false;  // the statement was written after "$$->"
};

}  // namespace pkm::program
