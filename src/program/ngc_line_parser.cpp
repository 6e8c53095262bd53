#include "program/ngc_line_parser.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "program/ngc_parameter_store.hpp"

namespace pkm::program::ngc {

using gcode::error_at;
using gcode::LineRef;

const char* to_string(OKeyword keyword) {
  switch (keyword) {
    case OKeyword::none:
      return "";
    case OKeyword::sub:
      return "sub";
    case OKeyword::endsub:
      return "endsub";
    case OKeyword::call:
      return "call";
    case OKeyword::do_:
      return "do";
    case OKeyword::while_:
      return "while";
    case OKeyword::repeat:
      return "repeat";
    case OKeyword::if_:
      return "if";
    case OKeyword::elseif:
      return "elseif";
    case OKeyword::else_:
      return "else";
    case OKeyword::endif:
      return "endif";
    case OKeyword::break_:
      return "break";
    case OKeyword::continue_:
      return "continue";
    case OKeyword::endwhile:
      return "endwhile";
    case OKeyword::endrepeat:
      return "endrepeat";
    case OKeyword::return_:
      return "return";
  }
  return "";
}

namespace {

constexpr int kLineMaxCallArguments = 30;

bool line_is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::string line_describe_bad_character(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u < 0x20 || u > 'z')
    return fmt::format("Bad character '\\{:03o}' used", u);  // as LinuxCNC: octal past 'z'
  return fmt::format("Bad character '{}' used", c);
}

// An N word at line.text[pos] ('n'): digits, optionally with a decimal part; its value is not kept.
Status line_skip_n_word(const NormalizedLine& line, std::size_t& pos, const LineRef& where) {
  const std::size_t start = pos++;
  const std::size_t digits = pos;
  while (line_is_digit(line.at(pos))) ++pos;
  if (pos == digits) return error_at(where, line.column(start), "Bad format unsigned integer");
  if (line.at(pos) == '.')
    for (++pos; line_is_digit(line.at(pos));) ++pos;
  return ok_status();
}

// The O-word keywords, tried in LinuxCNC's order (each a prefix test on what follows the number or name).
struct LineKeywordText {
  std::string_view text;
  OKeyword keyword;
};
constexpr LineKeywordText kLineKeywords[] = {
    {"sub", OKeyword::sub},
    {"endsub", OKeyword::endsub},
    {"call", OKeyword::call},
    {"do", OKeyword::do_},
    {"while", OKeyword::while_},
    {"repeat", OKeyword::repeat},
    {"if", OKeyword::if_},
    {"elseif", OKeyword::elseif},
    {"else", OKeyword::else_},
    {"endif", OKeyword::endif},
    {"break", OKeyword::break_},
    {"continue", OKeyword::continue_},
    {"endwhile", OKeyword::endwhile},
    {"endrepeat", OKeyword::endrepeat},
    {"return", OKeyword::return_},
};

Status line_parse_o_head(const NormalizedLine& line, std::size_t pos, const LineRef& where, ParsedLine& out) {
  OWordHead& o = out.o;
  o.column = line.column(pos);
  ++pos;
  o.named = line.at(pos) == '<';
  o.name.clear();
  if (o.named) {
    if (auto read = read_parameter_name(line, pos, where, o.name); !read) return read;
  } else {
    if (auto read = parse_real_value(line, pos, where, out.code, o.number); !read) return read;
  }
  o.keyword_column = line.column(pos);
  const std::string_view rest = std::string_view(line.text).substr(pos);
  for (const LineKeywordText& keyword : kLineKeywords) {
    if (rest.substr(0, keyword.text.size()) == keyword.text) {
      o.keyword = keyword.keyword;
      o.after = pos + keyword.text.size();
      return ok_status();
    }
  }
  const char c = line.at(pos);
  if (c != '(' && c != ';' && c != '\0')
    return error_at(where, line.column(pos), "Unknown control command in o word");
  o.keyword = OKeyword::none;
  o.after = pos;
  return ok_status();
}

bool line_starts_with_lower(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
  return true;
}

// Records the comment at line.text[pos] ('(') as the line's last one and moves past its ')'.
void line_read_comment(std::string_view raw, const NormalizedLine& line, std::size_t& pos, ParsedLine& out) {
  const std::size_t open = pos;
  while (line.at(pos) != ')') ++pos;  // normalize_line guarantees the ')'
  const auto raw_open = static_cast<std::size_t>(line.column(open) - 1);
  const auto raw_close = static_cast<std::size_t>(line.column(pos) - 1);
  ++pos;
  std::string_view text = raw.substr(raw_open + 1, raw_close - raw_open - 1);
  std::size_t start = 0;
  while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start]))) ++start;
  text = text.substr(start);
  struct Kind {
    std::string_view prefix;
    CommentKind kind;
  };
  static constexpr Kind kKinds[] = {{"msg,", CommentKind::msg},
                                    {"debug,", CommentKind::debug},
                                    {"print,", CommentKind::print},
                                    {"abort,", CommentKind::abort}};
  out.comment = CommentKind::plain;
  out.comment_text = text;
  out.comment_column = line.column(open);
  for (const Kind& kind : kKinds) {
    if (line_starts_with_lower(text, kind.prefix)) {
      out.comment = kind.kind;
      out.comment_text = text.substr(kind.prefix.size());
      return;
    }
  }
}

// The value after a word's letter or an assignment's '=': a plain number is kept as a constant.
Status line_parse_item_value(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                             ParsedLine& out, LineItem& item) {
  const std::size_t first = out.code.code.size();
  if (auto read = parse_real_value(line, pos, where, out.code, item.expression); !read) return read;
  if (out.code.code.size() == first + 1 && out.code.code[first].op == OpCode::number) {
    item.constant = true;
    item.value = out.code.code[first].value;
    out.code.code.pop_back();
  }
  return ok_status();
}

Status line_parse_assignment(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                             ParsedLine& out) {
  LineItem item;
  item.column = line.column(pos);
  ++pos;  // '#'
  if (line.at(pos) == '<') {
    item.kind = ItemKind::set_named;
    item.name_begin = static_cast<std::uint32_t>(out.code.names.size());
    if (auto read = read_parameter_name(line, pos, where, out.code.names); !read) return read;
    item.name_size = static_cast<std::uint32_t>(out.code.names.size() - item.name_begin);
  } else {
    item.kind = ItemKind::set_number;
    if (auto read = parse_real_value(line, pos, where, out.code, item.target); !read) return read;
  }
  if (line.at(pos) != '=')
    return error_at(where, line.column(pos), "Equal sign missing in parameter setting");
  ++pos;
  if (auto read = line_parse_item_value(line, pos, where, out, item); !read) return read;
  out.items.push_back(item);
  return ok_status();
}

Status line_parse_items(std::string_view raw, const NormalizedLine& line, std::size_t pos,
                        const LineRef& where, ParsedLine& out) {
  while (pos < line.size()) {
    const char c = line.at(pos);
    if (c == ';') break;
    if (c == '(') {
      line_read_comment(raw, line, pos, out);
    } else if (c == '#') {
      if (auto read = line_parse_assignment(line, pos, where, out); !read) return read;
    } else if ((c >= 'a' && c <= 'z' && c != 'n' && c != 'o') || c == '@' || c == '^' || c == '$') {
      LineItem item;
      item.letter = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
      item.column = line.column(pos);
      ++pos;
      if (auto read = line_parse_item_value(line, pos, where, out, item); !read) return read;
      out.items.push_back(item);
    } else {
      return error_at(where, line.column(pos), line_describe_bad_character(c));
    }
  }
  return ok_status();
}

}  // namespace

Status parse_line(std::string_view raw, const LineRef& where, NormalizedLine& line, ParsedLine& out,
                  bool o_word_only) {
  out.block_delete = false;
  out.percent = false;
  out.is_o_word = false;
  out.o_arguments.clear();
  out.items.clear();
  out.comment = CommentKind::none;
  out.comment_text = {};
  out.code.clear();
  if (auto normalized = normalize_line(raw, where, line); !normalized) return normalized;
  std::size_t pos = 0;
  if (line.at(0) == '/') {
    out.block_delete = true;
    pos = 1;
  }
  if (!out.block_delete && line.size() == 1 && line.at(0) == '%') {
    out.percent = true;
    return ok_status();
  }
  if (line.at(pos) == 'n')
    if (auto skipped = line_skip_n_word(line, pos, where); !skipped) return skipped;
  if (line.at(pos) == 'o') {
    out.is_o_word = true;
    return line_parse_o_head(line, pos, where, out);
  }
  if (o_word_only) return ok_status();
  return line_parse_items(raw, line, pos, where, out);
}

namespace {

bool line_is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// The number after a word's letter at raw[pos], blanks allowed anywhere in it (LinuxCNC removes them first):
// one optional sign, then digits and at most one point. False for anything the full parser must judge.
bool line_lex_simple_number(std::string_view raw, std::size_t& pos, double& value) {
  char digits[48];
  std::size_t count = 0;
  bool negative = false;
  bool sign = false;
  bool point = false;
  bool digit = false;
  for (; pos < raw.size(); ++pos) {
    const char c = raw[pos];
    if (line_is_blank(c)) continue;
    if ((c == '+' || c == '-') && !sign && count == 0) {
      sign = true;
      negative = c == '-';
    } else if (line_is_digit(c) || (c == '.' && !point)) {
      if (count + 1 >= sizeof digits) return false;
      digits[count++] = c;
      point = point || c == '.';
      digit = digit || c != '.';
    } else {
      break;
    }
  }
  if (!digit) return false;
  const auto [end, error] = std::from_chars(digits, digits + count, value, std::chars_format::fixed);
  if (error != std::errc() || end != digits + count) return false;
  if (negative) value = -value;
  return true;
}

}  // namespace

bool lex_simple_line(std::string_view raw, std::vector<gcode::Word>& words) {
  words.clear();
  std::size_t pos = 0;
  bool first = true;
  while (pos < raw.size()) {
    const char c = raw[pos];
    if (line_is_blank(c)) {
      ++pos;
      continue;
    }
    const char letter = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
    if (letter < 'A' || letter > 'Z' || letter == 'O') return false;
    if (letter == 'N' && !first) return false;
    const int column = static_cast<int>(pos) + 1;
    ++pos;
    double value = 0.0;
    if (!line_lex_simple_number(raw, pos, value)) return false;
    if (letter != 'N') words.push_back(gcode::Word{letter, value, column});
    first = false;
  }
  return true;
}

Status parse_o_tail(const NormalizedLine& line, const LineRef& where, ParsedLine& out) {
  std::size_t pos = out.o.after;
  const OKeyword keyword = out.o.keyword;
  ExpressionRef expression;
  if (keyword == OKeyword::if_ || keyword == OKeyword::elseif || keyword == OKeyword::while_ ||
      keyword == OKeyword::repeat) {
    if (line.at(pos) != '[')
      return error_at(where, line.column(pos),
                      fmt::format("Left bracket missing after '{}'", to_string(keyword)));
    if (auto read = parse_bracketed_expression(line, pos, where, out.code, expression); !read) return read;
    out.o_arguments.push_back(expression);
  } else if (keyword == OKeyword::return_ || keyword == OKeyword::endsub) {
    if (line.at(pos) == '[') {
      if (auto read = parse_bracketed_expression(line, pos, where, out.code, expression); !read) return read;
      out.o_arguments.push_back(expression);
    }
  } else if (keyword == OKeyword::call) {
    while (line.at(pos) == '[' || line.at(pos) == '(') {
      if (line.at(pos) == '(') {
        while (line.at(pos) != ')') ++pos;
        ++pos;
        continue;
      }
      if (out.o_arguments.size() >= kLineMaxCallArguments)
        return error_at(where, line.column(pos), "Too many subroutine parameters");
      if (auto read = parse_bracketed_expression(line, pos, where, out.code, expression); !read) return read;
      out.o_arguments.push_back(expression);
    }
  }
  while (pos < line.size()) {
    if (line.at(pos) == ';') break;
    if (line.at(pos) != '(') return error_at(where, line.column(pos), "Unexpected character after O-word");
    while (line.at(pos) != ')') ++pos;
    ++pos;
  }
  return ok_status();
}

namespace {

// A %d, %f or %.Nf directive at text[i] ('%'): sets `format` (digits after the point) and moves past it;
// anything else is copied as LinuxCNC copies it.
void line_read_format(std::string_view text, std::size_t& i, int& decimals, std::string& out) {
  ++i;  // '%'
  const char c = i < text.size() ? text[i] : '\0';
  if (c == 'd') {
    decimals = 0;
    ++i;
  } else if (c == 'f') {
    decimals = 4;
    ++i;
  } else if (c == '.') {
    ++i;
    if (i + 1 < text.size() && line_is_digit(text[i]) && text[i + 1] == 'f') {
      decimals = text[i] - '0';
      i += 2;
    } else {
      out.push_back('.');  // not a format: LinuxCNC keeps the point (and drops the '%')
    }
  } else {
    out.push_back('%');
  }
}

void line_append_value(std::optional<double> value, int decimals, std::string& out) {
  if (!value) {
    out += "######";
    return;
  }
  const double shown = std::fabs(*value) < 0.0001 ? 0.0 : *value;  // LinuxCNC avoids printing -0.000000
  const std::string text = fmt::format("{:.{}f}", shown, decimals);
  out += text.size() < 30 ? text : std::string("######");
}

}  // namespace

Status expand_parameters_in_comment(std::string_view text, const ParameterStore& store,
                                    const NamedParameterSource& names, const LineRef& where, int column,
                                    std::string& out) {
  out.clear();
  int decimals = 6;
  std::string name;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '%') {
      line_read_format(text, i, decimals, out);
      continue;
    }
    if (text[i] != '#') {
      out.push_back(text[i++]);
      continue;
    }
    ++i;
    if (i >= text.size()) return error_at(where, column, "Named parameter not terminated");
    if (line_is_digit(text[i])) {
      long number = 0;
      for (; i < text.size() && line_is_digit(text[i]); ++i)
        number = std::min(number * 10 + (text[i] - '0'), 100000L);
      const bool known = number < kParameterCount;
      line_append_value(known ? std::optional<double>(number == 0 ? 0.0 : store.get(static_cast<int>(number)))
                              : std::nullopt,
                        decimals, out);
    } else if (text[i] == '<') {
      name.clear();
      for (++i; i < text.size() && text[i] != '>'; ++i)
        if (!std::isspace(static_cast<unsigned char>(text[i])))
          name.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(text[i]))));
      if (i >= text.size()) return error_at(where, column, "Named parameter not terminated");
      ++i;
      line_append_value(names.named(name), decimals, out);
    } else {
      out.push_back('#');
    }
  }
  return ok_status();
}

}  // namespace pkm::program::ngc
