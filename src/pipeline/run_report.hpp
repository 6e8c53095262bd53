#pragma once
// The HTML report of a run as one more member of its output set: read back from the set's staging folder as
// `pkm report DIR` reads a finished run, so that the report shows exactly what the run's files say.
#include <string>

#include "core/result.hpp"
#include "io/output_set.hpp"

namespace pkm::pipeline {

/// Stages the report of the run staged in `outputs` as `report_path`; nothing when `report_path` is empty.
Status stage_run_report(OutputSet& outputs, const std::string& report_path);

}  // namespace pkm::pipeline
