#include "report/report_data.hpp"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <fstream>

#include "io/input_file.hpp"
#include "io/machine_file.hpp"
#include "report/calibration_report.hpp"
#include "report/csv_table.hpp"
#include "report/report_html.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"
#include "report/stiffness_plots.hpp"
#include "report/table_rows.hpp"
#include "report/workspace_report.hpp"

namespace pkm::report {

namespace fs = std::filesystem;

nlohmann::json chart_json(const std::string& id, const std::string& title, const std::string& y_label,
                          const std::string& y_unit, const MinMaxDecimator& data,
                          const std::vector<std::string>& names, bool with_path_length,
                          nlohmann::json limits) {
  nlohmann::json x = {{"time_s", json_numbers(data.time_s(), 9)}};
  if (with_path_length) x["s_mm"] = json_numbers(data.s_mm(), 9);
  nlohmann::json series = nlohmann::json::array();
  for (int k = 0; k < data.series(); ++k) {
    series.push_back({{"name", series_name(names[static_cast<std::size_t>(k)], y_unit)},
                      {"values", json_numbers(data.values(k))}});
  }
  return {{"id", id},          {"title", title},   {"y_label", y_label},         {"y_unit", y_unit},
          {"x", std::move(x)}, {"series", series}, {"limits", std::move(limits)}};
}

Result<long> expected_rows(const nlohmann::json& summary, const char* key, const std::string& csv_file) {
  if (summary.contains(key) && summary[key].is_number_integer() && summary[key].get<long>() > 0)
    return summary[key].get<long>();
  return count_csv_rows(csv_file);
}

nlohmann::json limit_line(const std::string& label, double value) {
  return {{"label", label}, {"value", json_number(value)}};
}

nlohmann::json travel_limit_lines(const ActuatorLimits& file_limits, const std::string& unit) {
  nlohmann::json lines = nlohmann::json::array();
  if (file_limits.max)
    lines.push_back(limit_line(fmt::format("max {:g} {}", *file_limits.max, unit), *file_limits.max));
  if (file_limits.min)
    lines.push_back(limit_line(fmt::format("min {:g} {}", *file_limits.min, unit), *file_limits.min));
  return lines;
}

nlohmann::json plus_minus_lines(const std::optional<double>& limit, const std::string& unit) {
  nlohmann::json lines = nlohmann::json::array();
  if (limit) {
    lines.push_back(limit_line(fmt::format("+{:g} {}", *limit, unit), *limit));
    lines.push_back(limit_line(fmt::format("−{:g} {}", *limit, unit), -*limit));
  }
  return lines;
}

std::vector<std::string> actuator_names(int count) {
  std::vector<std::string> names;
  for (int j = 1; j <= count; ++j) names.push_back(fmt::format("q{}", j));
  return names;
}

std::vector<std::string> drive_names(const std::string& prefix, int count, const std::string& suffix) {
  std::vector<std::string> names;
  for (int j = 1; j <= count; ++j) names.push_back(fmt::format("{}{}{}", prefix, j, suffix));
  return names;
}

std::string series_name(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : fmt::format("{} [{}]", name, unit);
}

nlohmann::json warning_entry(const std::string& what, int line) {
  nlohmann::json entry = {{"what", what}};
  if (line > 0) entry["line"] = line;
  return entry;
}

nlohmann::json table_row(const std::string& label, const std::string& value, int line) {
  nlohmann::json row = {{"label", label}, {"value", value}};
  if (line > 0) row["line"] = line;
  return row;
}

nlohmann::json program_lines(const std::string& file, const std::set<int>& lines) {
  nlohmann::json out = nlohmann::json::object();
  if (lines.empty() || !check_input_file(file, "part program")) return out;
  std::ifstream in(file);
  if (!in) return out;
  std::string text;
  int number = 0;
  auto wanted = lines.begin();
  while (wanted != lines.end() && std::getline(in, text)) {
    ++number;
    while (wanted != lines.end() && *wanted < number) ++wanted;
    if (wanted != lines.end() && *wanted == number) {
      if (!text.empty() && text.back() == '\r') text.pop_back();
      out[std::to_string(number)] = text.size() > 200 ? text.substr(0, 200) + "…" : text;
    }
  }
  return out;
}

std::string actuator_unit(const Machine& machine) {
  return machine.mechanism->actuators_are_angles() ? "deg" : "mm";
}

nlohmann::json machine_json(const Machine& machine) {
  const ActuatorLimits limits = limits_in_file_units(machine);
  nlohmann::json limit_json = nlohmann::json::object();
  if (limits.min) limit_json["min"] = *limits.min;
  if (limits.max) limit_json["max"] = *limits.max;
  if (limits.speed) limit_json["speed"] = *limits.speed;
  if (limits.accel) limit_json["accel"] = *limits.accel;
  return {{"file", machine.source},
          {"name", machine.name},
          {"type", std::string(to_string(machine.mechanism->type()))},
          {"actuator_unit", actuator_unit(machine)},
          {"actuator_names", actuator_names(machine.mechanism->actuator_count())},
          {"limits", limit_json}};
}

namespace {

// A calling line's text alone does not say which lines moved the tool: the plan's summary keeps where they
// were written ("subroutine_lines"); the report carries it for the lines it shows.
nlohmann::json subroutine_places(const nlohmann::json& summary, const std::set<int>& lines) {
  nlohmann::json called = nlohmann::json::object();
  if (!summary.is_object() || !summary.contains("subroutine_lines") ||
      !summary["subroutine_lines"].is_object())
    return called;
  for (const auto& item : summary["subroutine_lines"].items()) {
    const std::string& line = item.key();
    const nlohmann::json& places = item.value();
    int number = 0;
    const auto [end, error] = std::from_chars(line.data(), line.data() + line.size(), number);
    if (error != std::errc{} || end != line.data() + line.size() || !places.is_array()) continue;
    if (lines.count(number) > 0) called[line] = places;
  }
  return called;
}

}  // namespace

nlohmann::json report_document(const Machine& machine, ReportParts parts, SceneBuilder& scene) {
  std::set<int> lines = scene.lines();
  for (const auto& row : parts.table)
    if (row.contains("line")) lines.insert(row["line"].get<int>());
  // The run's own warnings (machine file, program notes, identification) are warnings of the report too: the
  // page's verdict is the worst of the limits and the warnings, so none of them may be left in the table
  // alone.
  if (parts.summary.is_object() && parts.summary.contains("warnings") && parts.summary["warnings"].is_array())
    for (const auto& w : parts.summary["warnings"])
      if (w.is_string()) parts.warnings.push_back(warning_entry(w.get<std::string>()));
  for (const nlohmann::json* list : {&parts.limits_reached, &parts.warnings})
    for (const auto& entry : *list)
      if (entry.contains("line")) lines.insert(entry["line"].get<int>());
  nlohmann::json program = {{"file", parts.program_file},
                            {"lines", program_lines(parts.program_file, lines)}};
  nlohmann::json called = subroutine_places(parts.summary, lines);
  if (!called.empty()) program["subroutine_lines"] = std::move(called);
  return {{"format", "pkm-report-1"},
          {"kind", parts.kind},
          {"title", parts.title},
          {"generated_by", "pkm " + parts.kind},
          {"machine", machine_json(machine)},
          {"program", std::move(program)},
          {"table", std::move(parts.table)},
          {"limits_reached", std::move(parts.limits_reached)},
          {"warnings", std::move(parts.warnings)},
          {"summary", std::move(parts.summary)},
          {"charts", std::move(parts.charts)},
          {"scene", scene.json()}};
}

Result<nlohmann::json> report_from_directory(const std::string& directory, const ReportOptions& options) {
  const fs::path dir(directory);
  const fs::path summary_path = dir / "summary.json";
  std::error_code ignored;
  if (!fs::exists(summary_path, ignored)) {
    return make_error(ErrorCode::io,
                      fmt::format("{}: no summary.json: not the output directory of pkm plan or "
                                  "pkm interpolate",
                                  directory));
  }
  auto summary_text = read_input_file(summary_path.string(), "run summary");
  if (!summary_text) return summary_text.error();
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(*summary_text);
  } catch (const nlohmann::json::exception& e) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: not valid JSON: {}", summary_path.string(), e.what()));
  }
  if (summary.is_object() && summary.value("kind", "") == "workspace")
    return workspace_report(directory, summary, options);
  if (summary.is_object() && summary.value("command", "") == "calibrate identify")
    return calibration_report(directory, summary, options);
  const bool planned = has_tick_tables(directory);
  // pkm stiffness: its points and a summary that names the stiffness model.
  const bool deflected =
      fs::exists(dir / "points.csv") && summary.contains("model") && summary.contains("points");
  const bool interpolated = fs::exists(dir / "steps.csv") && fs::exists(dir / "contour.csv");
  if (!planned && !interpolated && !deflected) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: neither ticks.h5 or actuators.csv + path.csv (pkm plan), steps.csv + "
                                  "contour.csv (pkm interpolate) nor points.csv (pkm stiffness)",
                                  directory));
  }
  std::string machine_file = options.machine_file;
  if (machine_file.empty()) {
    if (!summary.contains("machine") || !summary["machine"].is_string()) {
      Error error =
          make_error(ErrorCode::bad_input,
                     fmt::format("{}: machine: missing; name the machine file", summary_path.string()));
      error.location = ErrorLocation{summary_path.string(), 0, 0, "machine"};  // the caller may name the flag
      return error;
    }
    machine_file = summary["machine"].get<std::string>();
  }
  auto machine = load_machine_file(machine_file);
  if (!machine) {
    Error error =
        make_error(machine.error().code, fmt::format("{} (the machine of {}; name another machine file)",
                                                     machine.error().message, summary_path.string()));
    error.location = ErrorLocation{summary_path.string(), 0, 0, "machine"};
    return error;
  }
  RunFiles files{directory, summary,
                 options.program_file.empty() && summary.contains("program")
                     ? summary["program"].get<std::string>()
                     : options.program_file};
  if (deflected && !planned && !interpolated) {
    auto report = stiffness_report(*machine, files, options);
    if (!report) return report;
    if (Status added = add_stiffness_plots(directory, *report); !added) return added.error();
    return report;
  }
  // Both runs may share a directory; the summary says which came last.
  const bool interpolation_summary = summary.contains("method");
  if (interpolation_summary && !interpolated) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}: the summary is pkm interpolate's, but steps.csv or contour.csv is missing",
                    directory));
  }
  if (!interpolation_summary && !planned) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format(
            "{}: the summary is pkm plan's, but neither ticks.h5 nor actuators.csv and path.csv are there",
            directory));
  }
  auto report = interpolation_summary ? interpolate_report(*machine, files, options)
                                      : plan_report(*machine, files, options);
  if (!report) return report;
  // The stiffness plots, when the run's directory holds their files (stiffness_plots.hpp).
  if (Status added = add_stiffness_plots(directory, *report); !added) return added.error();
  return report;
}

Status write_directory_report(const std::string& directory, const std::string& file,
                              const ReportOptions& options) {
  auto data = report_from_directory(directory, options);
  if (!data) return data.error();
  return write_report_html(file, *data);
}

}  // namespace pkm::report
