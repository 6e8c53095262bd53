#pragma once
// Numbers, comments and event words as G-code text, for writing programs (gcode_writer.hpp). Numbers are
// plain decimals ([-]digits[.digits]): the G-code lexer takes no exponent, and it reads at most 63 digits.
#include <optional>
#include <string>
#include <string_view>

namespace pkm::program::gcode {

/// `value` with exactly `decimals` digits after the point ("12.5000"); never "-0.0000".
std::string fixed_number(double value, int decimals);

/// The shortest plain decimal that reads back as exactly `value` ("12.5", "0.00001"); nullopt when it would
/// be too long for the lexer (values below about 1e-30 or above 1e30) or `value` is not finite.
std::optional<std::string> exact_number(double value);

/// The value interpret_gcode reads from a number written by the functions above.
double number_value(std::string_view text);

/// "(text)", with parentheses left out (comments do not nest) and control characters made blanks (a comment
/// ends with its line).
std::string comment(std::string_view text);

/// An event as G-code: its own words when it is one ("M62 P1"), the comment that makes it for messages
/// ("MSG: hello" → "(MSG,hello)"), else a plain comment.
std::string event_text(std::string_view what);

/// Whether `what` is an event the G-code interpreter records and reads back the same from its own text:
/// blank-separated words S<number>, T<whole number> and M3 to M9 ("M3 S12000", "M6 T3", "M8", "T4").
bool is_gcode_event(std::string_view what);

}  // namespace pkm::program::gcode
