#include "report/servo_plots.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <string_view>

#include "io/input_file.hpp"
#include "report/report_data.hpp"
#include "report/run_reports.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

/// The files' times have six decimals; a row of another tick is at least one servo period away.
constexpr double kServoReportSameTickS = 2e-6;

/// servo_bode.csv's columns after drive and frequency_hz, in the file's order (pipeline/servo_program.cpp).
constexpr const char* kServoReportBodeColumns[] = {"speed_open_db",
                                                   "speed_open_deg",
                                                   "speed_closed_db",
                                                   "position_open_db",
                                                   "position_open_deg",
                                                   "position_closed_db",
                                                   "speed_open_sampled_db",
                                                   "speed_open_sampled_deg",
                                                   "position_open_sampled_db",
                                                   "position_open_sampled_deg",
                                                   "position_closed_sampled_db"};

enum ServoReportPlot { kServoReportFollowing, kServoReportContour };

// The summary's values (pkm's own file, but it may have been edited): NaN, 0 or "" when missing or of
// another type.
double servo_report_number(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number()
             ? object[key].get<double>()
             : std::numeric_limits<double>::quiet_NaN();
}

long servo_report_integer(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number_integer()
             ? object[key].get<long>()
             : 0L;
}

std::string servo_report_text(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string()
             ? object[key].get<std::string>()
             : std::string();
}

bool servo_report_flag(const nlohmann::json& object, const char* key, bool otherwise) {
  return object.is_object() && object.contains(key) && object[key].is_boolean() ? object[key].get<bool>()
                                                                                : otherwise;
}

const nlohmann::json& servo_report_member(const nlohmann::json& object, const char* key) {
  static const nlohmann::json none;
  return object.is_object() && object.contains(key) ? object[key] : none;
}

// "14, 15, 16" from an array of program lines; the first of them (0: none).
std::string servo_report_lines(const nlohmann::json& lines, int& first) {
  std::string text;
  first = 0;
  if (!lines.is_array()) return text;
  for (const auto& line : lines) {
    if (!line.is_number_integer()) continue;
    if (first == 0) first = line.get<int>();
    text += fmt::format("{}{}", text.empty() ? "" : ", ", line.get<int>());
  }
  return text;
}

// "0.01470 mm": four significant digits, enough for a table row ("—" for none).
std::string servo_report_value(double value, std::string_view unit) {
  return std::isfinite(value) ? fmt::format("{:.4g} {}", value, unit) : std::string("—");
}

Error servo_report_error(const std::string& where, const std::string& what) {
  return make_error(ErrorCode::bad_input, fmt::format("{}: {}", where, what));
}

// The drive with the largest (smallest, if `smallest`) finite figure at `path` of the drives' objects; -1 if
// none.
int servo_report_extreme_drive(const nlohmann::json& drives, const std::vector<const char*>& path,
                               bool smallest, double& value) {
  int best = -1;
  value = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < drives.size(); ++j) {
    const nlohmann::json* at = &drives[j];
    for (std::size_t k = 0; k + 1 < path.size(); ++k) at = &servo_report_member(*at, path[k]);
    const double v = servo_report_number(*at, path.back());
    if (!std::isfinite(v)) continue;
    if (best < 0 || (smallest ? v < value : v > value)) {
      best = static_cast<int>(j);
      value = v;
    }
  }
  return best;
}

// The coupling check of servo_summary.json: how many drives reach the ratio limit, the largest ratio, its
// drive
// (-1: none) and line, and the lines where the limit is reached.
struct ServoCoupling {
  double limit = 0.3;
  int coupled = 0;
  std::size_t drives = 0;
  double largest = 0.0;
  int drive = -1;
  int line = 0;
  std::set<int> lines;
};

ServoCoupling servo_report_coupling(const nlohmann::json& summary) {
  ServoCoupling c;
  const double limit = servo_report_number(summary, "coupling_ratio_limit");
  if (std::isfinite(limit)) c.limit = limit;
  const nlohmann::json& drives = servo_report_member(summary, "drives");
  if (!drives.is_array()) return c;
  c.drives = drives.size();
  for (const auto& drive : drives) {
    if (!(servo_report_number(drive, "max_coupling_ratio") >= c.limit)) continue;
    ++c.coupled;
    const nlohmann::json& lines = servo_report_member(drive, "coupled_lines");
    if (lines.is_array())
      for (const auto& line : lines)
        if (line.is_number_integer()) c.lines.insert(line.get<int>());
  }
  c.drive = servo_report_extreme_drive(drives, {"max_coupling_ratio"}, false, c.largest);
  if (c.drive >= 0)
    c.line = static_cast<int>(
        servo_report_integer(drives[static_cast<std::size_t>(c.drive)], "max_coupling_line"));
  return c;
}

// "6 of 6 drives, up to 7.6 (drive 2); lines 10, 11"
std::string servo_report_coupling_text(const ServoCoupling& c) {
  return fmt::format("{} of {} drives, up to {:.3g} (drive {}){}", c.coupled, c.drives, c.largest,
                     c.drive + 1,
                     c.lines.empty() ? std::string() : fmt::format("; lines {}", fmt::join(c.lines, ", ")));
}

}  // namespace

Result<nlohmann::json> servo_bode_json(const std::string& path, int drives) {
  CsvReader csv;
  if (Status opened = csv.open(path); !opened) return opened.error();
  auto drive_col = csv.require("drive");
  if (!drive_col) return drive_col.error();
  auto frequency_col = csv.require("frequency_hz");
  if (!frequency_col) return frequency_col.error();
  std::vector<int> columns;
  for (const char* name : kServoReportBodeColumns) {
    auto column = csv.require(name);
    if (!column) return column.error();
    columns.push_back(*column);
  }
  // Per drive: the frequencies, then one vector per column.
  std::vector<std::vector<std::vector<double>>> values(static_cast<std::size_t>(drives),
                                                       std::vector<std::vector<double>>(columns.size() + 1));
  std::vector<double> row;
  int previous = 0;
  while (csv.next(row)) {
    const double drive = row[static_cast<std::size_t>(*drive_col)];
    const std::string where = fmt::format("{}:{}", path, csv.line());
    if (!(drive >= 1.0 && drive <= drives && drive == std::floor(drive)))
      return servo_report_error(where, fmt::format("drive {}: not one of 1 … {}", drive, drives));
    const int j = static_cast<int>(drive);
    if (j < previous)
      return servo_report_error(
          where, fmt::format("drive {} after drive {} (the drives are in order)", j, previous));
    previous = j;
    const double frequency = row[static_cast<std::size_t>(*frequency_col)];
    if (!(frequency > 0.0) || !std::isfinite(frequency))
      return servo_report_error(where, "frequency_hz: not a positive number");
    auto& drive_values = values[static_cast<std::size_t>(j - 1)];
    drive_values[0].push_back(frequency);
    for (std::size_t c = 0; c < columns.size(); ++c)
      drive_values[c + 1].push_back(row[static_cast<std::size_t>(columns[c])]);
  }
  if (csv.error()) return *csv.error();
  nlohmann::json list = nlohmann::json::array();
  for (int j = 0; j < drives; ++j) {
    const auto& drive_values = values[static_cast<std::size_t>(j)];
    if (drive_values[0].empty()) return servo_report_error(path, fmt::format("no rows of drive {}", j + 1));
    nlohmann::json entry = {{"drive", j + 1}, {"frequency_hz", json_numbers(drive_values[0], 7)}};
    for (std::size_t c = 0; c < columns.size(); ++c)
      entry[kServoReportBodeColumns[c]] = json_numbers(drive_values[c + 1], 5);
    list.push_back(std::move(entry));
  }
  return list;
}

Status ServoTrace::open(const std::string& directory, const std::string& servo_directory,
                        const nlohmann::json& plan_summary, int drives, long expected_rows, int buckets) {
  directory_ = servo_directory.empty() ? directory : servo_directory;
  const fs::path dir(directory_);
  const std::string summary_path = (dir / kServoSummaryJson).string();
  std::error_code ignored;
  if (!fs::exists(summary_path, ignored)) return ok_status();
  auto text = read_input_file(summary_path, "servo summary");
  if (!text) return text.error();
  try {
    summary_ = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& e) {
    return servo_report_error(summary_path, fmt::format("not valid JSON: {}", e.what()));
  }
  if (servo_report_text(summary_, "kind") != "servo")
    return servo_report_error(summary_path, "not the summary of pkm servo (its kind is not \"servo\")");
  const nlohmann::json& drive_list = servo_report_member(summary_, "drives");
  if (!drive_list.is_array() || static_cast<int>(drive_list.size()) != drives) {
    return servo_report_error(summary_path,
                              fmt::format("{} drives, but the machine has {}",
                                          drive_list.is_array() ? drive_list.size() : 0, drives));
  }
  // The plan may have been run again since: its ticks are then not the servo run's.
  const long ticks = servo_report_integer(summary_, "ticks");
  const long plan_ticks = servo_report_integer(plan_summary, "ticks");
  if (ticks > 0 && plan_ticks > 0 && ticks != plan_ticks) {
    note_ = fmt::format("{} is of another run ({} ticks, the plan {}); run pkm servo again", summary_path,
                        ticks, plan_ticks);
    return ok_status();
  }
  drives_ = drives;
  unit_ = servo_report_text(summary_, "actuator_unit") == "deg" ? "deg" : "mm";
  if (Status opened = csv_.open((dir / kServoTicksCsv).string()); !opened) return opened;
  auto time = csv_.require("time_s");
  if (!time) return time.error();
  time_col_ = *time;
  auto contour = csv_.require("contour_error_mm");
  if (!contour) return contour.error();
  contour_col_ = *contour;
  for (int j = 1; j <= drives; ++j) {
    auto column = csv_.require(fmt::format("e{}_{}", j, unit_));
    if (!column) return column.error();
    error_cols_.push_back(*column);
  }
  error_.assign(static_cast<std::size_t>(drives), 0.0);
  plots_.emplace_back(drives, expected_rows, buckets);
  plots_.emplace_back(1, expected_rows, buckets);
  active_ = true;
  return ok_status();
}

Status ServoTrace::next(double time_s, double s_mm) {
  if (!active_) return ok_status();
  const bool more = csv_.next(row_);
  if (csv_.error()) return *csv_.error();
  if (!more || std::abs(row_[static_cast<std::size_t>(time_col_)] - time_s) > kServoReportSameTickS) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}:{}: not the tick at {:.6f} s of path.csv (a different run?)",
                                  csv_.path(), csv_.line() + (more ? 0 : 1), time_s));
  }
  for (std::size_t j = 0; j < error_.size(); ++j) error_[j] = row_[static_cast<std::size_t>(error_cols_[j])];
  plots_[kServoReportFollowing].add(time_s, s_mm, error_.data());
  plots_[kServoReportContour].add(time_s, s_mm, &row_[static_cast<std::size_t>(contour_col_)]);
  return ok_status();
}

Status ServoTrace::finish() {
  if (!active_) return ok_status();
  const bool more = csv_.next(row_);
  if (csv_.error()) return *csv_.error();
  if (more) {
    return make_error(ErrorCode::bad_input, fmt::format("{}:{}: more rows than path.csv (a different run?)",
                                                        csv_.path(), csv_.line()));
  }
  for (MinMaxDecimator& plot : plots_) plot.finish();
  return ok_status();
}

nlohmann::json ServoTrace::charts(const Machine& machine) const {
  nlohmann::json charts = nlohmann::json::array();
  if (!active_) return charts;
  // ± e_max, where the machine file gives every drive the same.
  std::optional<double> error_max;
  if (machine.servo.given() && machine.servo.drive_count == drives_) {
    const double first = machine.servo.drives[0].error_max;
    bool same = std::isfinite(first);
    for (int j = 1; j < drives_; ++j)
      same = same && machine.servo.drives[static_cast<std::size_t>(j)].error_max == first;
    if (same) error_max = first * (unit_ == "deg" ? 180.0 / std::numbers::pi : 1.0);
  }
  charts.push_back(chart_json("servo_following_error", "Following error (servo: set point − position)",
                              "following error", unit_, plots_[kServoReportFollowing],
                              drive_names("e", drives_), true, plus_minus_lines(error_max, unit_)));
  charts.push_back(chart_json("servo_contour_error", "Contour error (servo: tool from the commanded path)",
                              "contour error", "mm", plots_[kServoReportContour], {"contour error"}, true));
  return charts;
}

nlohmann::json ServoTrace::table_rows() const {
  nlohmann::json rows = nlohmann::json::array();
  if (!note_.empty()) rows.push_back(table_row("Servo run", "not shown: " + note_));
  if (!active_) return rows;
  const nlohmann::json& s = summary_;
  const nlohmann::json& drives = servo_report_member(s, "drives");
  rows.push_back(table_row(
      "Servo loops", fmt::format("{}, every {:g} ms, {}{}", servo_report_text(s, "tuning"),
                                 servo_report_number(s, "loop_period_s") * 1e3,
                                 servo_report_flag(s, "coupled", true) ? "coupled" : "decoupled",
                                 servo_report_flag(s, "machine_dynamics", true) ? "" : ", motors only")));
  rows.push_back(table_row(
      "Max contour error (servo)",
      fmt::format("{} (rms {})", servo_report_value(servo_report_number(s, "max_contour_error_mm"), "mm"),
                  servo_report_value(servo_report_number(s, "rms_contour_error_mm"), "mm")),
      static_cast<int>(servo_report_integer(s, "max_contour_line"))));
  rows.push_back(
      table_row("Max lag (servo)", servo_report_value(servo_report_number(s, "max_lag_s") * 1e3, "ms")));
  double value = 0.0;
  if (const int j = servo_report_extreme_drive(drives, {"max_following_error"}, false, value); j >= 0) {
    rows.push_back(table_row(
        "Max following error", fmt::format("{} (drive {})", servo_report_value(value, unit_), j + 1),
        static_cast<int>(servo_report_integer(drives[static_cast<std::size_t>(j)], "max_following_line"))));
  }
  // The limits of the loops, per drive where they acted.
  bool acted = false;
  for (std::size_t j = 0; j < drives.size(); ++j) {
    const long error_clamps = servo_report_integer(drives[j], "error_clamps");
    const long command_clamps = servo_report_integer(drives[j], "command_clamps");
    if (error_clamps + command_clamps == 0) continue;
    acted = true;
    int first = 0;
    const std::string lines = servo_report_lines(servo_report_member(drives[j], "clamp_lines"), first);
    rows.push_back(table_row(fmt::format("Servo limits, drive {}", j + 1),
                             fmt::format("e_max {}×, u_max {}× (loop steps){}", error_clamps, command_clamps,
                                         lines.empty() ? "" : "; lines " + lines),
                             first));
  }
  if (!acted) rows.push_back(table_row("Servo limits (e_max, u_max)", "never acted"));
  // The coupling check (one row): the drives at or above the limit, the largest ratio and the lines, else the
  // largest ratio.
  const ServoCoupling c = servo_report_coupling(s);
  if (c.drive >= 0) {
    if (c.coupled > 0) {
      rows.push_back(
          table_row(fmt::format("Coupling ratio ≥ {:g}", c.limit), servo_report_coupling_text(c), c.line));
    } else {
      rows.push_back(table_row("Max coupling ratio",
                               fmt::format("{:.3g} (drive {}), below {:g}", c.largest, c.drive + 1, c.limit),
                               c.line));
    }
  }
  std::string margins;
  for (const char* loop : {"speed", "position"}) {
    const int j = servo_report_extreme_drive(
        drives,
        {loop == std::string("speed") ? "speed_loop" : "position_loop", "sampled", "phase_margin_deg"}, true,
        value);
    if (j >= 0)
      margins += fmt::format("{}{} {:.1f}° (drive {})", margins.empty() ? "" : ", ", loop, value, j + 1);
  }
  if (!margins.empty()) rows.push_back(table_row("Smallest phase margin (sampled)", margins));
  const nlohmann::json& worst = servo_report_member(s, "worst_lines");
  if (worst.is_array() && !worst.empty()) {
    std::string text;
    int first = 0;
    for (const auto& entry : worst) {
      const int line = static_cast<int>(servo_report_integer(entry, "line"));
      if (first == 0) first = line;
      text += fmt::format("{}{} ({})", text.empty() ? "" : ", ", line,
                          servo_report_value(servo_report_number(entry, "contour_error_mm"), "mm"));
    }
    rows.push_back(table_row("Worst lines (servo)", text, first));
  }
  if (const long failures = servo_report_integer(s, "fk_failures"); failures > 0)
    rows.push_back(table_row("Ticks without contour error (FK failed)", std::to_string(failures)));
  return rows;
}

nlohmann::json ServoTrace::warnings() const {
  nlohmann::json warnings = nlohmann::json::array();
  if (!note_.empty()) warnings.push_back(warning_entry("servo run not shown: " + note_));
  if (!active_) return warnings;
  // At or above the ratio the machine's inertia on a drive is no longer small against its motor's: the loops,
  // each tuned to its own drive, are coupled through the machine (docs/servo.md). Nothing was clamped, so it
  // is no limit reached, but the loops' figures are then less certain than they look.
  const ServoCoupling c = servo_report_coupling(summary_);
  if (c.coupled > 0) {
    warnings.push_back(warning_entry(
        fmt::format("servo: coupling ratio ≥ {:g} on {}: the drives' loops are coupled through the machine",
                    c.limit, servo_report_coupling_text(c)),
        c.line > 0 || c.lines.empty() ? c.line : *c.lines.begin()));
  }
  return warnings;
}

nlohmann::json ServoTrace::limit_entries() const {
  nlohmann::json entries = nlohmann::json::array();
  if (!active_) return entries;
  const nlohmann::json& drives = servo_report_member(summary_, "drives");
  for (std::size_t j = 0; j < drives.size(); ++j) {
    const long error_clamps = servo_report_integer(drives[j], "error_clamps");
    const long command_clamps = servo_report_integer(drives[j], "command_clamps");
    if (error_clamps + command_clamps == 0) continue;
    std::string what = fmt::format("drive {} servo:", j + 1);
    if (error_clamps > 0)
      what += fmt::format(" position error clamped at e_max in {} loop steps", error_clamps);
    if (command_clamps > 0)
      what += fmt::format("{} command clamped at u_max in {} loop steps", error_clamps > 0 ? ";" : "",
                          command_clamps);
    int first = 0;
    servo_report_lines(servo_report_member(drives[j], "clamp_lines"), first);
    nlohmann::json entry = {{"what", what}, {"severity", "reached"}};
    if (first > 0) entry["line"] = first;
    entries.push_back(std::move(entry));
  }
  return entries;
}

Result<nlohmann::json> ServoTrace::object() const {
  if (!active_) return nlohmann::json(nullptr);
  auto bode = servo_bode_json((fs::path(directory_) / kServoBodeCsv).string(), drives_);
  if (!bode) return bode.error();
  const double loop_period_s = servo_report_number(summary_, "loop_period_s");
  return nlohmann::json{
      {"files", {{"summary", kServoSummaryJson}, {"ticks", kServoTicksCsv}, {"bode", kServoBodeCsv}}},
      {"actuator_unit", unit_},
      {"nyquist_hz",
       json_number(loop_period_s > 0.0 ? 0.5 / loop_period_s : std::numeric_limits<double>::quiet_NaN())},
      {"charts", {"servo_following_error", "servo_contour_error"}},
      {"summary", summary_},
      {"bode", std::move(*bode)}};
}

}  // namespace pkm::report
