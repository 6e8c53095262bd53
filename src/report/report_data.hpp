#pragma once
// Building the report's data (docs/report-data.md) from a run's output directory: `pkm plan` (ticks.h5 or
// actuators.csv + path.csv, summary.json) or `pkm interpolate` (steps.csv, contour.csv, summary.json). The
// machine and program files are the ones the summary names, unless given. Everything long is decimated on
// the way in, so a run of any length gives a page that opens quickly.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "report/decimator.hpp"
#include "report/scene.hpp"

namespace pkm::report {

struct ReportOptions {
  std::string machine_file;  ///< instead of the summary's
  std::string program_file;  ///< instead of the summary's
  int chart_buckets = 2000;  ///< two points per bucket and series
  int frames = 1500;         ///< animation frames
  int path_points = 40000;   ///< points of each 3-D path
  /// Where `pkm servo` wrote servo.csv, servo_bode.csv and servo_summary.json for a plan's report
  /// (servo_plots.hpp); "": the run's own directory.
  std::string servo_directory;
  /// Where `pkm simulate` wrote simulate.csv and simulate_summary.json (simulate_plots.hpp); "": the run's
  /// own directory.
  std::string simulate_directory;
};

/// The report data of the run in `directory`.
Result<nlohmann::json> report_from_directory(const std::string& directory, const ReportOptions& options = {});
/// report_from_directory() written as one HTML page to `file` (report_html.hpp); nothing is written on
/// failure.
Status write_directory_report(const std::string& directory, const std::string& file,
                              const ReportOptions& options = {});

// Pieces shared by the report builders (plan, interpolate, optimize).

/// One chart of the report from a decimator: series `names`, x over time and (if `with_path_length`) over s.
/// Each series is named by its quantity with the chart's unit (series_name): the legend then reads "P1 [N]".
nlohmann::json chart_json(const std::string& id, const std::string& title, const std::string& y_label,
                          const std::string& y_unit, const MinMaxDecimator& data,
                          const std::vector<std::string>& names, bool with_path_length,
                          nlohmann::json limits = nlohmann::json::array());
/// How many rows `csv_file` has: the summary's count under `key` (ticks, periods) when it gives one, so that
/// sizing the decimation costs no extra pass over a file of gigabytes; otherwise counted.
Result<long> expected_rows(const nlohmann::json& summary, const char* key, const std::string& csv_file);
/// A horizontal line on a chart.
nlohmann::json limit_line(const std::string& label, double value);
/// Lines at the ends of the actuators' travel ("max 900 mm", "min 350 mm"), where the machine gives them.
nlohmann::json travel_limit_lines(const ActuatorLimits& file_limits, const std::string& unit);
/// Symmetric lines at ±limit ("+100 mm/s", "−100 mm/s"); none without a limit.
nlohmann::json plus_minus_lines(const std::optional<double>& limit, const std::string& unit);
/// "q1" … "qn".
std::vector<std::string> actuator_names(int count);
/// `prefix`1`suffix` … `prefix`n`suffix`: one name per drive ("P1 static", "power 1").
std::vector<std::string> drive_names(const std::string& prefix, int count, const std::string& suffix = "");
/// "P1 [N]": a series' name with its unit; the name alone where the quantity has none.
std::string series_name(const std::string& name, const std::string& unit);
/// An entry of the report's `warnings`: something to look at that is no limit reached ("line" 0: none).
nlohmann::json warning_entry(const std::string& what, int line = 0);
/// A row of the summary table; `line` 0 means none.
nlohmann::json table_row(const std::string& label, const std::string& value, int line = 0);
/// The parts of a report that every kind of run fills in.
struct ReportParts {
  std::string kind;  ///< "plan", "interpolate", "optimize"
  std::string title;
  std::string program_file;  ///< for the source text of the lines the report refers to
  nlohmann::json table = nlohmann::json::array();
  nlohmann::json limits_reached = nlohmann::json::array();
  /// warning_entry()s; report_document() adds the summary's own "warnings" (strings) after them.
  nlohmann::json warnings = nlohmann::json::array();
  nlohmann::json summary = nlohmann::json::object();
  nlohmann::json charts = nlohmann::json::array();
};
/// The whole report object (docs/report-data.md), with the source text of every program line that the scene's
/// frames, the table, the limits and the warnings refer to.
nlohmann::json report_document(const Machine& machine, ReportParts parts, SceneBuilder& scene);
/// The source text of `lines` of a program file (missing file: empty).
nlohmann::json program_lines(const std::string& file, const std::set<int>& lines);
/// "mm" or "deg".
std::string actuator_unit(const Machine& machine);
/// The "machine" object of the report.
nlohmann::json machine_json(const Machine& machine);

}  // namespace pkm::report
