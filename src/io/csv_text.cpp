#include "io/csv_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "io/printable_text.hpp"

namespace pkm::csv_text {

bool Lines::next(std::string_view& line) {
  if (empty_) {
    if (number_ > 0) return false;
    line = {};
    number_ = 1;
    return true;
  }
  if (!walker_.next(line, number_)) return false;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
    text.remove_suffix(1);
  return text;
}

bool is_blank(std::string_view line) {
  return trim(line).empty();
}

std::vector<Field> split_row(std::string_view row) {
  std::vector<Field> fields;
  Fields cursor(row);
  for (std::string_view raw; cursor.next(raw);) {
    std::size_t lead = 0;
    while (lead < raw.size() && (raw[lead] == ' ' || raw[lead] == '\t')) ++lead;
    fields.push_back({trim(raw), static_cast<int>(cursor.offset() + lead) + 1});
  }
  return fields;
}

bool directive(std::string_view line, Directive& out) {
  std::size_t at = 0;
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  if (at == line.size() || line[at] != '#') return false;
  ++at;
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  const std::size_t key_start = at;
  while (at < line.size() && (std::isalnum(static_cast<unsigned char>(line[at])) || line[at] == '_')) ++at;
  if (at == key_start || at == line.size() || line[at] != ':') return false;
  out.key = line.substr(key_start, at - key_start);
  out.key_column = static_cast<int>(key_start) + 1;
  ++at;
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  out.value = trim(line.substr(at));
  out.value_column = static_cast<int>(at) + 1;
  return true;
}

Error error_at(const std::string& source, int line, int column, std::string_view key,
               std::string_view message) {
  return Error{ErrorCode::bad_input,
               fmt::format("{}:{}:{}: {}: {}", source, line, column, printable_text(key, 80), message),
               ErrorLocation{source, line, column, std::string(key)}};
}

Result<double> number(const std::string& source, int line, const Field& field, std::string_view key,
                      std::string_view unit) {
  std::string_view text = field.text;
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [stop, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || stop != text.data() + text.size()) {
    return error_at(source, line, field.column, key,
                    fmt::format("expected a number in {}, got '{}'", unit, printable_text(field.text, 80)));
  }
  if (!std::isfinite(value))
    return error_at(
        source, line, field.column, key,
        fmt::format("expected a finite number in {}, got '{}'", unit, printable_text(field.text, 80)));
  if (std::abs(value) > kMaxMagnitude) {
    return error_at(source, line, field.column, key,
                    fmt::format("{} {} is beyond ±{:g} {}: a typing error or a unit mix-up?", field.text,
                                unit, kMaxMagnitude, unit));
  }
  return value;
}

}  // namespace pkm::csv_text
