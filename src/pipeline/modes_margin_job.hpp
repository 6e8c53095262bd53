#pragma once
// `pkm modes-margin` as one library call: a part program planned on a machine, the assembly-mode margin and
// the other assembly modes at poses along it (workspace/modes_margin_program.hpp), and, if asked, every
// pose's margin and modes written to a CSV file.
#include <nlohmann/json.hpp>
#include <string>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "workspace/modes_margin_program.hpp"

namespace pkm::pipeline {

struct ModesMarginJob {
  std::string program_path;        ///< G-code, or CL data (told apart by content)
  ProgramOptions program_options;  ///< tool table, subroutine path, parameter file
  workspace::ProgramModesMarginOptions margin;
  std::string out_path;   ///< the CSV of every pose; empty: not written
  ProgressSink progress;  ///< told the phase now and then
};

struct ModesMarginJobResult {
  workspace::ProgramModesMargin margin;
  nlohmann::json summary;  ///< formats::modes_margin_summary_json, with "out" when the CSV was written
};

/// Everything is computed before the file is touched: a failure leaves a previous CSV as it was.
Result<ModesMarginJobResult> run_modes_margin_job(const Machine& machine, const ModesMarginJob& job);

}  // namespace pkm::pipeline
