#pragma once
// The redundancy-law options shared by `pkm optimize` and `pkm plan --law`.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "core/result.hpp"
#include "redundancy/optimize_program.hpp"

namespace pkm::cli {

struct RedundancyArguments {
  std::string law;
  std::string free = "spin";
  std::string bounds;
  double step_mm = 1.0;
  std::string parts = "fixed";
  double improvement = 0.01;
  double min_part_mm = 1.0;
  int patience = 3;
  std::string load;
  std::string solver = "greedy";
  std::string energy_accounting = "no-recovery";
  std::string force_model = "statics";
  double force_limit_N = 0.0;
  double max_rate_deg_per_mm = 0.0;
};

/// Adds --law (required when `law_required`), --free, --bounds, --step-mm, --parts, --improvement,
/// --min-part-mm, --patience, --load, --solver,
/// --energy-accounting, --force-limit and --max-rate to a subcommand.
void add_redundancy_options(CLI::App& command, RedundancyArguments& arguments, bool law_required);

/// --bounds: LO,HI for every free coordinate, or LO,HI,LO,HI,LO,HI for each of three (degrees).
Result<redundancy::FreeBounds> parse_bounds(const std::string& text);

/// The options, or an error naming the bad argument.
Result<redundancy::OptimizeOptions> redundancy_options(const RedundancyArguments& arguments);

}  // namespace pkm::cli
