#include "number_options.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <string_view>

#include "io/printable_text.hpp"

namespace pkm::cli {

namespace {

std::string number_option_value(double value, const std::string& unit) {
  return unit.empty() ? fmt::format("{:g}", value) : fmt::format("{:g} {}", value, unit);
}

enum class OptionNumber { ok, not_a_number, too_large, too_small };

// The whole text must be one number; from_chars also reads "nan" and "inf", which the range check refuses.
// A number beyond a double's range leaves `value` untouched (0): it must be refused as what it is, not
// checked as 0.
OptionNumber parse_option_number(std::string_view text, double& value) {
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || end != text.data() + text.size()) return OptionNumber::not_a_number;
  if (error == std::errc::result_out_of_range) {
    // The exponent's sign says which way: 1e999 overflows, 1e-999 underflows.
    const std::size_t e = text.find_first_of("eE");
    return e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-' ? OptionNumber::too_small
                                                                                    : OptionNumber::too_large;
  }
  return error == std::errc() ? OptionNumber::ok : OptionNumber::not_a_number;
}

}  // namespace

std::string describe_range(const NumberRange& range) {
  const std::string low = fmt::format("{} {:g}", range.low_inclusive ? "≥" : ">", range.low);
  const std::string high = fmt::format("{} {:g}", range.high_inclusive ? "≤" : "<", range.high);
  std::string text = std::isinf(range.high) ? low : fmt::format("{} and {}", low, high);
  if (!range.unit.empty()) text += " " + range.unit;
  return text;
}

NumberRange number_range(const pipeline::ParameterRange& range) {
  return {range.low, range.high, range.low_inclusive, true, std::string(range.unit), range.whole};
}

CLI::Validator number_in(NumberRange range) {
  const std::string description = describe_range(range);
  return CLI::Validator(
      [range, description](std::string& text) -> std::string {
        double value = 0.0;
        switch (parse_option_number(text, value)) {
          case OptionNumber::not_a_number:
            return fmt::format("expected a number {}, got '{}'", description, printable_text(text));
          case OptionNumber::too_large:
            return fmt::format("must be {}, got {} (too large for any number)", description,
                               printable_text(text));
          case OptionNumber::too_small:
            return fmt::format("must be {}, got {} (too small to tell from 0: write 0)", description,
                               printable_text(text));
          case OptionNumber::ok:
            break;
        }
        if (!std::isfinite(value))
          return fmt::format("must be a finite number {}, got {}", description, printable_text(text));
        const bool above_low = range.low_inclusive ? value >= range.low : value > range.low;
        const bool below_high = range.high_inclusive ? value <= range.high : value < range.high;
        if (!above_low || !below_high)
          return fmt::format("must be {}, got {}", description, number_option_value(value, range.unit));
        if (range.whole && std::floor(value) != value)
          return fmt::format("must be a whole number {}, got {}", description, printable_text(text));
        return {};
      },
      description);
}

int exit_for_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  // --help and --help-all arrive as "errors" with exit code 0; CLI11 prints them.
  if (error.get_exit_code() == 0) return app.exit(error);
  std::string command = "pkm";
  for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
    sub = sub->get_subcommands().front();
    command += " " + sub->get_name();
  }
  std::cerr << command << ": error: " << printable_text(error.what()) << "\n"
            << "Run with --help for more information.\n";
  return 2;
}

}  // namespace pkm::cli
