#include "program/cl_number.hpp"

#include <charconv>
#include <cmath>

namespace pkm::program {

std::optional<double> parse_cl_number(std::string_view text) {
  // from_chars rejects a leading '+', which CAM systems do write.
  const bool plus = !text.empty() && text.front() == '+';
  if (plus) text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  // Only digits and '.' may start the mantissa; this keeps out "inf", "nan" and a second sign.
  const char first = !plus && text.front() == '-' && text.size() > 1 ? text[1] : text.front();
  if (!(first == '.' || (first >= '0' && first <= '9'))) return std::nullopt;
  double value = 0.0;
  const char* const end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value, std::chars_format::general);
  if (ec != std::errc{} || stop != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace pkm::program
