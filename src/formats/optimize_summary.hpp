#pragma once
// The summary of a drive control law's choice of the free coordinates (`pkm optimize`, a plan's "law"):
// const_sum_mm, opt_sum_mm, peak_force_const_N, peak_force_opt_N, energy_const_J, energy_opt_J, the free
// coordinates' start, bounds and range, and each solver's metrics.
#include <nlohmann/json.hpp>

#include "redundancy/optimize_program.hpp"

namespace pkm::formats {

nlohmann::json optimize_summary_json(const redundancy::OptimizeResult& result,
                                     const redundancy::OptimizeOptions& options);

}  // namespace pkm::formats
