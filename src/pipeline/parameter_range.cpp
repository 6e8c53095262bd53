#include "pipeline/parameter_range.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace pkm::pipeline {

Status check_in_range(const ParameterRange& range, double value) {
  const bool inside = (range.low_inclusive ? value >= range.low : value > range.low) && value <= range.high &&
                      (!range.whole || std::floor(value) == value);
  if (inside) return ok_status();
  const std::string unit = range.unit.empty() ? std::string() : fmt::format(" {}", range.unit);
  return make_error(
      ErrorCode::bad_input,
      fmt::format("{} {}: expected {}{}{} … {}{}", range.name, value, range.whole ? "a whole number " : "",
                  range.low_inclusive ? "" : "> ", range.low, range.high, unit));
}

}  // namespace pkm::pipeline
