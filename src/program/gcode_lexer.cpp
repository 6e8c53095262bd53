#include "program/gcode_lexer.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstddef>

namespace pkm::program::gcode {

Error error_at(const LineRef& where, int column, std::string_view message) {
  Error error = make_error(ErrorCode::bad_input,
                           fmt::format("{}:{}:{}: {}", where.source, where.line, column, message));
  error.location = ErrorLocation{std::string(where.source), where.line, column, ""};
  return error;
}

namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
char to_upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
bool is_letter(char c) {
  const char u = to_upper(c);
  return u >= 'A' && u <= 'Z';
}
int column_of(std::size_t index) {
  return static_cast<int>(index) + 1;
}

std::string describe(char c) {
  if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
    return fmt::format("byte 0x{:02x}", static_cast<unsigned char>(c));
  return fmt::format("character '{}'", c);
}

// Reads the number after the letter at text[letter_at]; `pos` is just after the letter and is left just after
// the number. Blanks inside the number are skipped, as LinuxCNC does ("X 1 0 . 5" is X10.5).
Status read_number(std::string_view text, std::size_t letter_at, std::size_t& pos, const LineRef& where,
                   double& value) {
  const char letter = to_upper(text[letter_at]);
  const int column = column_of(letter_at);
  char digits[64];
  std::size_t count = 0;
  int digit_count = 0;
  int dots = 0;
  bool negative = false;
  bool sign = false;
  std::size_t p = pos;
  while (p < text.size() && is_blank(text[p])) ++p;
  if (p < text.size() && (text[p] == '+' || text[p] == '-')) {
    negative = text[p] == '-';
    sign = true;
    ++p;
  }
  std::size_t end = p;  // just after the last character that belongs to the number
  while (p < text.size()) {
    const char c = text[p];
    if (is_digit(c) || c == '.') {
      if (count + 1 >= sizeof digits)
        return error_at(where, column, fmt::format("number too long in {} word", letter));
      digits[count++] = c;
      if (c == '.') {
        ++dots;
      } else {
        ++digit_count;
      }
      end = ++p;
    } else if (is_blank(c)) {
      ++p;
    } else {
      break;
    }
  }
  if (digit_count == 0) {
    if (!sign && dots == 0) {
      std::size_t q = pos;
      while (q < text.size() && is_blank(text[q])) ++q;
      if (q < text.size() && text[q] == '#')
        return error_at(where, column_of(q), "parameters (#) are not supported");
      if (q < text.size() && text[q] == '[')
        return error_at(where, column_of(q), "expressions ([...]) are not supported");
      return error_at(where, column, fmt::format("{} word without a number", letter));
    }
    return error_at(where, column, fmt::format("bad number '{}'", text.substr(letter_at, end - letter_at)));
  }
  if (dots > 1)
    return error_at(where, column, fmt::format("bad number '{}'", text.substr(letter_at, end - letter_at)));
  const auto [ptr, ec] = std::from_chars(digits, digits + count, value, std::chars_format::fixed);
  if (ec != std::errc() || ptr != digits + count)
    return error_at(where, column, fmt::format("bad number '{}'", text.substr(letter_at, end - letter_at)));
  if (negative) value = -value;
  pos = end;
  return ok_status();
}

}  // namespace

Status lex_line(std::string_view text, const LineRef& where, LexedLine& out) {
  out.words.clear();
  out.block_delete = false;
  out.percent = false;
  std::size_t p = 0;
  while (p < text.size() && is_blank(text[p])) ++p;
  if (p < text.size() && text[p] == '/') {
    out.block_delete = true;
    ++p;
  }
  if (p < text.size() && text[p] == '%' && !out.block_delete) {
    std::size_t q = p + 1;
    while (q < text.size() && is_blank(text[q])) ++q;
    if (q == text.size() || text[q] == ';') {
      out.percent = true;
      return ok_status();
    }
    return error_at(where, column_of(p), "'%' must stand alone on its line");
  }
  bool first_word = true;
  while (p < text.size()) {
    const char c = text[p];
    if (is_blank(c)) {
      ++p;
      continue;
    }
    if (c == ';') break;
    if (c == '(') {
      std::size_t q = p + 1;
      while (q < text.size() && text[q] != ')') {
        if (text[q] == '(') return error_at(where, column_of(q), "nested comment");
        ++q;
      }
      if (q == text.size()) return error_at(where, column_of(p), "comment not closed on its line");
      p = q + 1;
      continue;
    }
    if (is_letter(c)) {
      const char letter = to_upper(c);
      const std::size_t letter_at = p;
      if (letter == 'O')
        return error_at(where, column_of(p), "O-words (subroutines, loops, conditions) are not supported");
      ++p;
      double value = 0.0;
      if (auto read = read_number(text, letter_at, p, where, value); !read) return read.error();
      if (letter == 'N') {
        if (!first_word)
          return error_at(where, column_of(letter_at), "N word (block number) must open the block");
      } else {
        out.words.push_back(Word{letter, value, column_of(letter_at)});
      }
      first_word = false;
      continue;
    }
    if (c == '#') return error_at(where, column_of(p), "parameters (#) are not supported");
    if (c == '[') return error_at(where, column_of(p), "expressions ([...]) are not supported");
    return error_at(where, column_of(p), "unexpected " + describe(c));
  }
  return ok_status();
}

}  // namespace pkm::program::gcode
