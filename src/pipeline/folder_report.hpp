#pragma once
// pkm report DIR: the HTML report of a run's output folder. The folder must hold one complete output set of
// a command the report understands (io/output_manifest.hpp); a page written into that folder (the default
// DIR/report.html) joins the folder's set, so that the folder still reads as one set afterwards.
#include <string>
#include <vector>

#include "core/result.hpp"
#include "report/report_data.hpp"

namespace pkm::pipeline {

/// The commands whose folders pkm report reads.
const std::vector<std::string>& report_folder_commands();

/// Reads DIR, checks its set and writes the page to `file`; nothing is written on error.
Status write_folder_report(const std::string& directory, const std::string& file,
                           const report::ReportOptions& options);

}  // namespace pkm::pipeline
