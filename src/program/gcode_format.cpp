#include "program/gcode_format.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

namespace pkm::program::gcode {

namespace {

// Well below the lexer's 63 digits; longer exact numbers mean absurd values (a dwell of 1e40 s).
constexpr std::size_t kFormatLongestExactNumber = 40;

bool format_all_digits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// digits[.digits], as the lexer reads a number without its sign.
bool format_is_plain_number(std::string_view text) {
  const std::size_t dot = text.find('.');
  if (dot == std::string_view::npos) return format_all_digits(text);
  return format_all_digits(text.substr(0, dot)) && format_all_digits(text.substr(dot + 1));
}

bool format_is_event_word(std::string_view word) {
  if (word.size() < 2) return false;
  const std::string_view number = word.substr(1);
  switch (word[0]) {
    case 'S':
      return format_is_plain_number(number);
    case 'T':
      return format_all_digits(number);
    case 'M': {
      // The M-codes the interpreter records as events: pauses, spindle, tools, coolant, overrides, I/O,
      // modal state and user M-codes.
      if (!format_all_digits(number) || number.size() > 3) return false;
      const int m = std::stoi(std::string(number));
      return m == 0 || m == 1 || (m >= 3 && m <= 9) || m == 19 || (m >= 48 && m <= 53) || m == 60 ||
             (m >= 61 && m <= 68) || (m >= 70 && m <= 73) || (m >= 100 && m <= 199);
    }
    case 'P':
    case 'Q':
    case 'E':
    case 'L':
      return format_is_plain_number(number);
    default:
      return false;
  }
}

}  // namespace

std::string fixed_number(double value, int decimals) {
  std::string text = fmt::format("{:.{}f}", value, decimals);
  // A tiny negative value rounds to "-0.0000", which reads as zero anyway but looks like a bug.
  if (text.front() == '-' && text.find_first_not_of("0.", 1) == std::string::npos) text.erase(0, 1);
  return text;
}

std::optional<std::string> exact_number(double value) {
  if (!std::isfinite(value)) return std::nullopt;
  if (value == 0.0) return std::string("0");  // also for -0.0
  std::array<char, 400> buffer{};
  // Without a precision, to_chars writes the shortest representation that reads back as the same double.
  const auto [end, error] =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed);
  if (error != std::errc()) return std::nullopt;
  const std::size_t length = static_cast<std::size_t>(end - buffer.data());
  if (length > kFormatLongestExactNumber) return std::nullopt;
  return std::string(buffer.data(), length);
}

double number_value(std::string_view text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::fixed);
  return value;
}

std::string event_text(std::string_view what) {
  if (is_gcode_event(what)) return std::string(what);
  // Messages come back as the comments that made them, so that reading the program again gives them again.
  // The interpreter writes them "KIND: text" (ngc_executor.cpp).
  for (const std::string_view kind : {"MSG: ", "DEBUG: ", "PRINT: "}) {
    if (what.substr(0, kind.size()) == kind) {
      std::string out = comment(what.substr(kind.size()));
      out.insert(1, std::string(kind.substr(0, kind.size() - 2)) + ",");
      return out;
    }
  }
  return comment(what);
}

std::string comment(std::string_view text) {
  std::string out = "(";
  for (const char c : text) {
    if (c == '(' || c == ')') continue;
    const auto byte = static_cast<unsigned char>(c);
    out += byte < 0x20 || byte == 0x7f ? ' ' : c;
  }
  out += ')';
  return out;
}

bool is_gcode_event(std::string_view what) {
  bool any = false;
  while (!what.empty()) {
    const std::size_t blank = what.find(' ');
    const std::string_view word = what.substr(0, blank);
    if (!word.empty()) {
      if (!format_is_event_word(word)) return false;
      any = true;
    }
    if (blank == std::string_view::npos) break;
    what.remove_prefix(blank + 1);
  }
  return any;
}

}  // namespace pkm::program::gcode
