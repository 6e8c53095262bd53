#pragma once
// The redundancy-law arguments that pkm.optimize and pkm.plan(law=...) take, as the CLI's --law, --free,
// --bounds, --step-mm, --parts, --improvement, --min-part-mm, --solver, --energy-accounting, --force-model,
// --force-limit, --max-rate and --load.
#include <array>
#include <optional>
#include <string>

#include "core/result.hpp"
#include "redundancy/optimize_program.hpp"

namespace pkm::python {

struct LawArguments {
  std::string law;  ///< increment | force | energy | rotation | potential
  std::string free = "spin";
  std::vector<std::array<double, 2>> bounds_deg;  ///< none, one for every free coordinate, or one for each
  double step_mm = 1.0;
  std::string solver = "greedy";
  std::string energy_accounting = "no-recovery";
  std::string force_model = "statics";
  std::optional<double> force_limit_N;
  std::optional<double> max_rate_deg_per_mm;
  std::string load;             ///< the CLI's --load text: key=value list or @FILE.yaml; empty: none
  std::string parts = "fixed";  ///< fixed | adaptive (redundancy/block_subdivision.hpp)
  double improvement = 0.01;
  double min_part_mm = 1.0;
  int patience = 3;
};

/// The options, or a bad_input error naming the argument (as the Python keyword).
Result<redundancy::OptimizeOptions> optimize_options(const LawArguments& arguments);

/// The process load of a --load text (empty: none).
Result<statics::LoadModel> load_model(const std::string& spec);

}  // namespace pkm::python
