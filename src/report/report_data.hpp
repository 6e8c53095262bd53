#pragma once
// Building the report's data (docs/report-data.md) from a run's output directory: `pkm plan` (actuators.csv,
// path.csv, summary.json) or `pkm interpolate` (steps.csv, contour.csv, summary.json). The machine and
// program files are the ones the summary names, unless given. Everything long is decimated on the way in, so
// a run of any length gives a page that opens quickly.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "report/decimator.hpp"

namespace pkm::report {

struct ReportOptions {
  std::string machine_file;  ///< instead of the summary's
  std::string program_file;  ///< instead of the summary's
  int chart_buckets = 2000;  ///< two points per bucket and series
  int frames = 1500;         ///< animation frames
  int path_points = 40000;   ///< points of each 3-D path
};

/// The report data of the run in `directory`.
Result<nlohmann::json> report_from_directory(const std::string& directory, const ReportOptions& options = {});
/// report_from_directory() written as one HTML page to `file` (report_html.hpp); nothing is written on
/// failure.
Status write_directory_report(const std::string& directory, const std::string& file,
                              const ReportOptions& options = {});

// Pieces shared by the report builders (plan, interpolate, optimize).

/// One chart of the report from a decimator: series `names`, x over time and (if `with_path_length`) over s.
nlohmann::json chart_json(const std::string& id, const std::string& title, const std::string& y_label,
                          const std::string& y_unit, const MinMaxDecimator& data,
                          const std::vector<std::string>& names, bool with_path_length,
                          nlohmann::json limits = nlohmann::json::array());
/// A horizontal line on a chart.
nlohmann::json limit_line(const std::string& label, double value);
/// A row of the summary table; `line` 0 means none.
nlohmann::json table_row(const std::string& label, const std::string& value, int line = 0);
/// The source text of `lines` of a program file (missing file: empty).
nlohmann::json program_lines(const std::string& file, const std::set<int>& lines);
/// "mm" or "deg".
std::string actuator_unit(const Machine& machine);
/// The "machine" object of the report.
nlohmann::json machine_json(const Machine& machine);

}  // namespace pkm::report
