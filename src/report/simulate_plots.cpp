#include "report/simulate_plots.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "io/input_file.hpp"
#include "report/report_data.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

// The files' times have six decimals; a row of another tick is at least one servo period away.
constexpr double kSimulateReportSameTickS = 2e-6;
constexpr const char* kSimulateParts[] = {"servo_mm", "elastic_mm", "load_mm", "drives_mm"};
constexpr const char* kSimulatePoints[] = {"x_actual_mm",  "y_actual_mm",  "z_actual_mm",
                                           "x_program_mm", "y_program_mm", "z_program_mm"};

Error simulate_report_error(const std::string& where, const std::string& what) {
  return make_error(ErrorCode::bad_input, fmt::format("{}: {}", where, what));
}

double simulate_report_number(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number()
             ? object[key].get<double>()
             : std::numeric_limits<double>::quiet_NaN();
}

// "0.01470 mm (line 38)" of a part's object in the summary.
std::string simulate_report_part(const nlohmann::json& part) {
  const double max_mm = simulate_report_number(part, "max_mm");
  if (!std::isfinite(max_mm)) return "—";
  const double line = simulate_report_number(part, "max_line");
  return std::isfinite(line) && line > 0 ? fmt::format("{:.4g} mm (line {:.0f})", max_mm, line)
                                         : fmt::format("{:.4g} mm", max_mm);
}

}  // namespace

Status SimulateTrace::open(const std::string& directory, const nlohmann::json& plan_summary,
                           long expected_rows, int buckets) {
  const fs::path dir(directory);
  const std::string summary_path = (dir / kSimulateSummaryJson).string();
  std::error_code ignored;
  if (!fs::exists(summary_path, ignored)) return ok_status();
  auto text = read_input_file(summary_path, "simulation summary");
  if (!text) return text.error();
  try {
    summary_ = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& e) {
    return simulate_report_error(summary_path, fmt::format("not valid JSON: {}", e.what()));
  }
  if (!summary_.is_object() || summary_.value("kind", "") != "simulate")
    return simulate_report_error(summary_path,
                                 "not the summary of pkm simulate (its kind is not \"simulate\")");
  const double ticks = simulate_report_number(summary_, "ticks");
  const double plan_ticks = simulate_report_number(plan_summary, "ticks");
  if (std::isfinite(ticks) && std::isfinite(plan_ticks) && ticks != plan_ticks) {
    note_ = fmt::format("{} is of another run ({:.0f} ticks, the plan {:.0f}); run pkm simulate again",
                        summary_path, ticks, plan_ticks);
    return ok_status();
  }
  split_ = summary_.value("split", false);
  if (Status opened = csv_.open((dir / kSimulateTicksCsv).string()); !opened) return opened;
  auto time = csv_.require("time_s");
  if (!time) return time.error();
  time_col_ = *time;
  auto contour = csv_.require("contour_error_mm");
  if (!contour) return contour.error();
  error_cols_.push_back(*contour);
  for (const char* part : kSimulateParts) {
    if (!split_) break;
    auto column = csv_.require(part);
    if (!column) return column.error();
    error_cols_.push_back(*column);
  }
  for (const char* point : kSimulatePoints) {
    auto column = csv_.require(point);
    if (!column) return column.error();
    deviation_cols_.push_back(*column);
  }
  values_.assign(error_cols_.size() + 3, 0.0);
  plots_.emplace_back(static_cast<int>(error_cols_.size()), expected_rows, buckets);
  plots_.emplace_back(3, expected_rows, buckets);
  active_ = true;
  return ok_status();
}

Status SimulateTrace::next(double time_s, double s_mm) {
  if (!active_) return ok_status();
  const bool more = csv_.next(row_);
  if (csv_.error()) return *csv_.error();
  if (!more || std::abs(row_[static_cast<std::size_t>(time_col_)] - time_s) > kSimulateReportSameTickS) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}:{}: not the tick at {:.6f} s of the path table (a different run?)",
                                  csv_.path(), csv_.line() + (more ? 0 : 1), time_s));
  }
  const std::size_t errors = error_cols_.size();
  for (std::size_t k = 0; k < errors; ++k) values_[k] = row_[static_cast<std::size_t>(error_cols_[k])];
  for (std::size_t c = 0; c < 3; ++c) {
    values_[errors + c] = row_[static_cast<std::size_t>(deviation_cols_[c])] -
                          row_[static_cast<std::size_t>(deviation_cols_[c + 3])];
  }
  plots_[0].add(time_s, s_mm, values_.data());
  plots_[1].add(time_s, s_mm, values_.data() + errors);
  return ok_status();
}

Status SimulateTrace::finish() {
  if (!active_) return ok_status();
  const bool more = csv_.next(row_);
  if (csv_.error()) return *csv_.error();
  if (more) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}:{}: more rows than the path table (a different run?)", csv_.path(), csv_.line()));
  }
  for (MinMaxDecimator& plot : plots_) plot.finish();
  return ok_status();
}

nlohmann::json SimulateTrace::charts() const {
  nlohmann::json charts = nlohmann::json::array();
  if (!active_) return charts;
  std::vector<std::string> names{"contour error"};
  if (split_) names.insert(names.end(), {"servo part", "elastic part", "load part", "drives part"});
  charts.push_back(chart_json("simulate_contour_error",
                              "Contour error of the machine in the loop (simulate), and its parts",
                              "contour error", "mm", plots_[0], names, true));
  charts.push_back(chart_json("simulate_deviation", "Tool's actual point − commanded point (simulate)",
                              "deviation", "mm", plots_[1], {"x", "y", "z"}, true));
  return charts;
}

nlohmann::json SimulateTrace::table_rows() const {
  nlohmann::json rows = nlohmann::json::array();
  if (!note_.empty()) rows.push_back(table_row("Machine simulation", "not shown: " + note_));
  if (!active_) return rows;
  const nlohmann::json contour = summary_.value("contour_error", nlohmann::json::object());
  const double line = simulate_report_number(contour, "max_line");
  rows.push_back(
      table_row("Max contour error (simulate)",
                fmt::format("{:.4g} mm (rms {:.4g} mm){}", simulate_report_number(contour, "max_mm"),
                            simulate_report_number(contour, "rms_mm"),
                            summary_.value("load", false) ? ", under the process load" : ""),
                std::isfinite(line) ? static_cast<int>(line) : 0));
  if (split_) {
    const nlohmann::json parts = summary_.value("parts", nlohmann::json::object());
    std::string text;
    for (const char* name : {"servo", "elastic", "load", "drives"}) {
      text += fmt::format("{}{} {}", text.empty() ? "" : "; ", name,
                          simulate_report_part(parts.value(name, nlohmann::json::object())));
    }
    rows.push_back(table_row("Contour error's parts (simulate, largest)", text));
  }
  return rows;
}

}  // namespace pkm::report
