#pragma once
// `pkm optimize` (and Python's pkm.optimize) as one library call: a part program whose operation leaves
// coordinates free in, the free coordinates chosen by a drive control law (redundancy/optimize_program.hpp),
// the rewritten program written with A B C and, if asked, the HTML report, together or not at all.
#include <nlohmann/json.hpp>
#include <string>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "redundancy/optimize_program.hpp"

namespace pkm::pipeline {

struct OptimizeJob {
  std::string program_path;        ///< G-code (X Y Z) or CL data (told apart by content)
  ProgramOptions program_options;  ///< tool table, subroutine path, parameter file
  redundancy::OptimizeOptions options;
  std::string out_path;     ///< the rewritten G-code program; empty: not written
  std::string report_path;  ///< empty: no report
  ProgressSink progress;    ///< told the phase now and then
};

struct OptimizeJobResult {
  program::CanonicalProgram program;  ///< as read, before the law
  redundancy::OptimizeResult result;
  nlohmann::json summary;  ///< formats::optimize_summary_json with the machine and the written program
};

/// Refuses a load whose `lines` name no line of the program (naming the option), a program that leaves no
/// coordinate free, or a law no pose along it can hold.
Result<OptimizeJobResult> run_optimize_job(const Machine& machine, const OptimizeJob& job);

}  // namespace pkm::pipeline
