#pragma once
// The report of a `pkm optimize` run (docs/report.md): the free coordinates the law chose against holding
// them at their start values, the largest strut increment per step, peak strut forces and drive energy of
// both, and the 3-D animation of the optimised program. Built from the result in memory: the post-processor's
// own output is the new program.
#include <nlohmann/json.hpp>
#include <string>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "redundancy/optimize_program.hpp"
#include "report/report_data.hpp"

namespace pkm::report {

Result<nlohmann::json> optimize_report(const Machine& machine, const program::CanonicalProgram& program,
                                       const redundancy::OptimizeResult& result,
                                       const redundancy::OptimizeOptions& options,
                                       const nlohmann::json& summary, const std::string& output_file,
                                       const ReportOptions& report_options = {});

}  // namespace pkm::report
