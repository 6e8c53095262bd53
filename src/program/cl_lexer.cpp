#include "program/cl_lexer.hpp"

#include <algorithm>
#include <array>
#include <iterator>

namespace pkm::program {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}

// Statements whose argument is free text: a comma or slash in it is not a separator.
bool is_text_word(std::string_view upper_word) {
  constexpr std::array<std::string_view, 4> words = {"PARTNO", "PPRINT", "INSERT", "TPRINT"};
  return std::find(words.begin(), words.end(), upper_word) != words.end();
}

// Upper case, runs of blanks collapsed to one: "tool  path" -> "TOOL PATH".
void normalise_word(std::string_view raw, std::string& out) {
  out.clear();
  bool blank = false;
  for (const char c : raw) {
    if (is_blank(c)) {
      blank = true;
      continue;
    }
    if (blank && !out.empty()) out.push_back(' ');
    blank = false;
    out.push_back(ascii_upper(c));
  }
}

}  // namespace

int ClLexer::line_count() const {
  const auto newlines = std::count(text_.begin(), text_.end(), '\n');
  const bool open_last = !text_.empty() && text_.back() != '\n';
  return static_cast<int>(newlines) + (open_last ? 1 : 0);
}

bool ClLexer::gather() {
  buffer_.clear();
  segments_.clear();
  comment_ = {};
  comment_at_ = {};
  annotation_ = false;
  bool continued = false;  // the previous line ended in '$'
  bool& annotation = annotation_;
  while (pos_ < text_.size()) {
    std::size_t eol = text_.find('\n', pos_);
    if (eol == std::string_view::npos) eol = text_.size();
    std::string_view line = text_.substr(pos_, eol - pos_);
    pos_ = eol + 1;
    ++line_;
    std::size_t first = 0;
    while (first < line.size() && is_blank(line[first])) ++first;
    if (!continued && line.substr(first).starts_with("$$->")) {
      // Pro/CLfile writes statements for the post-processor as "$$-> WORD / values": read as a statement,
      // continued with '$' over plain lines like any other.
      first += 4;
      annotation = true;
    } else if (!continued && line.substr(first).starts_with("$$")) {
      comment_ = trim(line.substr(first + 2));
      comment_at_ = {line_, static_cast<int>(first) + 1};
      return true;
    }
    if (const std::size_t comment = line.find("$$", first); comment != std::string_view::npos) {
      line = line.substr(0, comment);
    }
    while (first < line.size() && is_blank(line[first])) ++first;
    line = line.substr(first);
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    if (line.empty()) continue;  // blank or comment line (also inside a continued statement)

    const bool continues = line.back() == '$';
    // Keep the blanks before a '$' so that continued free text does not run words together.
    const std::string_view piece = continues ? line.substr(0, line.size() - 1) : line;
    const int column = static_cast<int>(first) + 1;
    if (!continued && !continues) {  // the common case: one line, no copy
      segments_.push_back({0, line_, column});
      statement_ = piece;
      return true;
    }
    segments_.push_back({buffer_.size(), line_, column});
    buffer_.append(piece);
    continued = continues;
    if (!continues) break;
  }
  if (segments_.empty()) return false;
  statement_ = buffer_;  // also a statement whose last line still ended in '$' at the end of the text
  return true;
}

ClPosition ClLexer::position_of(const char* p) const {
  const auto offset = static_cast<std::size_t>(p - statement_.data());
  // The last segment starting at or before the offset. A binary search: a statement continued over n lines
  // has n segments and about n arguments, and a scan per argument made reading it quadratic.
  auto after = std::upper_bound(segments_.begin(), segments_.end(), offset,
                                [](std::size_t at, const Segment& s) { return at < s.offset; });
  const Segment& segment = after == segments_.begin() ? *after : *std::prev(after);
  return {segment.line, segment.column + static_cast<int>(offset - segment.offset)};
}

void ClLexer::split(ClStatement& out) const {
  out.args.clear();
  out.has_slash = false;
  out.is_text = false;
  out.is_comment = false;
  out.is_annotation = annotation_;
  if (comment_at_.line > 0) {  // a whole-line "$$ comment"
    out.word.clear();
    out.is_comment = true;
    out.at = comment_at_;
    out.text = comment_;
    out.text_at = comment_at_;
    return;
  }
  const std::string_view s = trim(statement_);  // a first line of just "$" leaves the blanks of the next
  out.at = position_of(s.data());

  std::size_t token_end = 0;
  while (token_end < s.size() && is_word_char(s[token_end])) ++token_end;
  normalise_word(s.substr(0, token_end), out.word);
  if (is_text_word(out.word)) {  // PPRINT text / PPRINT/text
    std::string_view rest = trim(s.substr(token_end));
    if (!rest.empty() && rest.front() == '/') {
      out.has_slash = true;
      rest = trim(rest.substr(1));
    }
    out.is_text = true;
    out.text = rest;
    out.text_at = position_of(rest.data());
    return;
  }

  const std::size_t slash = s.find('/');
  if (slash == std::string_view::npos) {  // a bare word: RAPID, END, END-OF-PATH (or something unknown)
    normalise_word(s, out.word);
    out.text = {};
    out.text_at = out.at;
    return;
  }
  out.has_slash = true;
  normalise_word(s.substr(0, slash), out.word);
  const std::string_view rest = s.substr(slash + 1);
  out.text = trim(rest);
  out.text_at = out.text.empty() ? position_of(rest.data()) : position_of(out.text.data());
  if (out.text.empty()) return;  // "WORD/" has no arguments

  std::size_t start = 0;
  while (true) {
    const std::size_t comma = rest.find(',', start);
    const std::string_view raw =
        rest.substr(start, comma == std::string_view::npos ? rest.npos : comma - start);
    const std::string_view value = trim(raw);
    // A missing value points at where it should have been: just after the previous separator.
    out.args.push_back({value, position_of(value.empty() ? raw.data() : value.data())});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
}

bool ClLexer::next(ClStatement& out) {
  if (!gather()) return false;
  split(out);
  return true;
}

}  // namespace pkm::program
