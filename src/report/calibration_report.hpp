#pragma once
// The report of a `pkm calibrate identify` run (parameters.csv, residuals.csv, poses.csv, summary.json;
// docs/calibration.md): the summary as the report's table, the measured poses in the 3-D view (the tool point
// the drawing would give beside the one the identified model gives, coloured by the difference), and the
// `calibration` object the page draws (web/src/calibration.js): every residual before and after, and the
// parameter table with the identified values and their standard deviations. Read back from the files, as
// every report is.
#include <nlohmann/json.hpp>
#include <string>

#include "core/result.hpp"
#include "report/report_data.hpp"

namespace pkm::report {

/// The report of the run in `directory` whose summary is `summary` ("command": "calibrate identify"); the
/// machine file is the summary's unless options.machine_file names another.
Result<nlohmann::json> calibration_report(const std::string& directory, const nlohmann::json& summary,
                                          const ReportOptions& options);

}  // namespace pkm::report
