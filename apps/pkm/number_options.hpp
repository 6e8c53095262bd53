#pragma once
// Checks for the numeric command-line options. CLI11 alone would take "nan", "inf" or "1e308" for a double
// and let the value reach the planner; each numeric option gets a range here instead, checked on the text
// the user typed, so the message names the option ("--tolerance: must be ≥ 0 mm, got -1") and pkm exits 2.
#include <CLI/CLI.hpp>
#include <string>

#include "pipeline/parameter_range.hpp"

namespace pkm::cli {

/// The accepted interval of a numeric option and its unit for messages ("mm", "%", "" for a count).
struct NumberRange {
  double low;
  double high;
  bool low_inclusive = true;   ///< false: low itself is refused ("> 0")
  bool high_inclusive = true;  ///< false: high itself is refused ("< 1")
  std::string unit;
  bool whole = false;  ///< only whole numbers (counts)
};

/// A library parameter's range (pipeline/parameter_range.hpp) as an option's: one definition for both.
NumberRange number_range(const pipeline::ParameterRange& range);
/// A CLI11 validator: the option's text must be one finite number inside `range`.
CLI::Validator number_in(NumberRange range);

/// "> 0 and ≤ 200 %": the range in words, for messages and help texts.
std::string describe_range(const NumberRange& range);

/// A failed CLI11 parse (an unknown option, a missing argument, a refused value): the message on stderr and
/// the exit code, 2 as for any other bad input (0 for --help).
int exit_for_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace pkm::cli
