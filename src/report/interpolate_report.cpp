// The report of a `pkm interpolate` run: actuator positions from the drives' position codes, steps per period
// against the step rate, the contour error per period against ρ_max, and the 3-D animation with the executed
// path coloured by its error, from steps.csv and contour.csv.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/units.hpp"
#include "report/csv_table.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

double summary_number(const nlohmann::json& summary, const std::string& key) {
  return summary.contains(key) && summary[key].is_number() ? summary[key].get<double>()
                                                           : std::numeric_limits<double>::quiet_NaN();
}

int summary_line(const nlohmann::json& summary, const std::string& key) {
  return summary.contains(key) && summary[key].is_number_integer() ? summary[key].get<int>() : 0;
}

// The columns of contour.csv the report reads: time, line, the error, the executed and the programmed point.
Result<std::array<int, 9>> contour_csv_columns(CsvReader& contour) {
  static const char* const kContourColumns[] = {"time_s", "line",      "max_error_mm", "x_mm",     "y_mm",
                                                "z_mm",   "path_x_mm", "path_y_mm",    "path_z_mm"};
  std::array<int, 9> c{};
  for (std::size_t k = 0; k < 9; ++k) {
    auto index = contour.require(kContourColumns[k]);
    if (!index) return index.error();
    c[k] = *index;
  }
  return c;
}

// Positions from the drives' position codes, steps per period against the step rate, and the contour error
// against ρ_max.
nlohmann::json interpolate_charts(const MinMaxDecimator& positions, const MinMaxDecimator& step_counts,
                                  const MinMaxDecimator& errors, int n, const std::string& unit,
                                  const ActuatorLimits& limits, double max_step_rate, double period_s,
                                  double rho_max) {
  nlohmann::json step_limits = nlohmann::json::array(), error_limits = nlohmann::json::array();
  if (max_step_rate > 0.0) {
    const double per_period = std::floor(max_step_rate * period_s);
    step_limits.push_back(
        limit_line(fmt::format("+{:g} steps ({:g} Hz)", per_period, max_step_rate), per_period));
    step_limits.push_back(limit_line(fmt::format("−{:g} steps", per_period), -per_period));
  }
  if (rho_max > 0.0) error_limits.push_back(limit_line(fmt::format("ρ_max {:g} mm", rho_max), rho_max));
  nlohmann::json charts = nlohmann::json::array();
  charts.push_back(chart_json("actuator_positions", "Actuator positions (drive position codes × step)",
                              "position", unit, positions, actuator_names(n), false,
                              travel_limit_lines(limits, unit)));
  charts.push_back(chart_json("steps_per_period", "Steps per period (sign: direction)", "steps", "steps",
                              step_counts, drive_names("drive ", n), false, step_limits));
  charts.push_back(chart_json("contour_error", "Contour error (largest in each period)", "error", "mm",
                              errors, {"contour error"}, false, error_limits));
  return charts;
}

// The summary table of an interpolation run, from its summary.json.
nlohmann::json interpolate_table(const nlohmann::json& sm, double step, const std::string& unit,
                                 double rho_max, const RunFiles& files, const Machine& machine) {
  nlohmann::json table = nlohmann::json::array();
  table.push_back(table_row("Method", sm.value("method", std::string("?"))));
  table.push_back(table_row("Periods / period", fmt::format("{} / {} ms", sm.value("periods", 0L),
                                                            summary_number(sm, "period_ms"))));
  table.push_back(table_row("Drive step", with_unit(step, unit)));
  table.push_back(
      table_row("Real / ideal time", fmt::format("{} / {}", with_unit(summary_number(sm, "real_time_s"), "s"),
                                                 with_unit(summary_number(sm, "ideal_time_s"), "s"))));
  table.push_back(table_row("Max contour error", with_unit(summary_number(sm, "max_contour_error_mm"), "mm"),
                            summary_line(sm, "max_contour_error_line")));
  table.push_back(
      table_row("RMS contour error", with_unit(summary_number(sm, "rms_contour_error_mm"), "mm")));
  table.push_back(table_row("Start / end error",
                            fmt::format("{} / {}", with_unit(summary_number(sm, "start_error_mm"), "mm"),
                                        with_unit(summary_number(sm, "end_error_mm"), "mm"))));
  table.push_back(table_row("Max error after the first period",
                            with_unit(summary_number(sm, "max_contour_error_after_first_period_mm"), "mm")));
  table.push_back(table_row("Contour tolerance ρ_max", with_unit(rho_max, "mm")));
  table.push_back(table_row("Max steps per period", with_unit(summary_number(sm, "max_steps_per_period"), ""),
                            summary_line(sm, "max_steps_line")));
  table.push_back(
      table_row("Compute per period (max / mean)",
                fmt::format("{} / {}", with_unit(summary_number(sm, "max_compute_us_per_period"), "µs"),
                            with_unit(summary_number(sm, "mean_compute_us_per_period"), "µs"))));
  table.push_back(
      table_row("Compute per period (p50 / p99 / p99.9)",
                fmt::format("{} / {} / {}", with_unit(summary_number(sm, "period_time_us_p50"), "µs"),
                            with_unit(summary_number(sm, "period_time_us_p99"), "µs"),
                            with_unit(summary_number(sm, "period_time_us_p99_9"), "µs"))));
  table.push_back(table_row("Program", files.program));
  table.push_back(table_row("Machine file", machine.source));
  return table;
}

// The contour error beyond ρ_max (exceeded) and the drives' step rate (reached).
nlohmann::json interpolate_limits_reached(const nlohmann::json& sm, double rho_max, double max_step_rate,
                                          double period_s) {
  nlohmann::json reached = nlohmann::json::array();
  const double max_error = summary_number(sm, "max_contour_error_mm");
  if (rho_max > 0.0 && max_error > rho_max) {
    reached.push_back(
        {{"what", fmt::format("contour error {:.3g} mm beyond ρ_max = {:g} mm", max_error, rho_max)},
         {"line", summary_line(sm, "max_contour_error_line")},
         {"time_s", summary_number(sm, "max_contour_error_time_s")},
         {"severity", "exceeded"}});
  }
  const double max_steps = summary_number(sm, "max_steps_per_period");
  if (max_step_rate > 0.0 && max_steps >= 0.99 * std::floor(max_step_rate * period_s) - 1.0) {
    reached.push_back({{"what", fmt::format("{:g} steps in a period: the drives' step rate {:g} Hz",
                                            max_steps, max_step_rate)},
                       {"line", summary_line(sm, "max_steps_line")},
                       {"severity", "reached"}});
  }
  return reached;
}

// The drives' columns of steps.csv and what a row says of each drive: the position (code × step), the steps
// in the period, and how close both come to the limits and the step rate.
struct DriveCodes {
  std::vector<int> step_columns, position_columns;
  double step = 0.0, period_s = 0.0, max_step_rate = 0.0;
  ActuatorLimits limits;

  void read(const std::vector<double>& row, std::vector<double>& q, std::vector<double>& counts,
            std::vector<double>& closeness) const {
    for (std::size_t j = 0; j < q.size(); ++j) {
      q[j] = row[static_cast<std::size_t>(position_columns[j])] * step;
      counts[j] = row[static_cast<std::size_t>(step_columns[j])];
      const double rate = counts[j] / period_s;
      double near = limit_closeness(limits, q[j], counts[j] * step / period_s,
                                    std::numeric_limits<double>::quiet_NaN());
      if (max_step_rate > 0.0) near = std::max(near, std::min(1.0, std::abs(rate) / max_step_rate));
      closeness[j] = near;
    }
  }
};

Result<DriveCodes> drive_codes(CsvReader& steps, int n) {
  DriveCodes codes;
  for (int j = 1; j <= n; ++j) {
    auto steps_column = steps.require(fmt::format("steps_{}", j));
    auto position_column = steps.require(fmt::format("position_{}", j));
    if (!steps_column) return steps_column.error();
    if (!position_column) return position_column.error();
    codes.step_columns.push_back(*steps_column);
    codes.position_columns.push_back(*position_column);
  }
  return codes;
}

// Where the drives' steps put the platform, for the frames: FK from the previous frame's pose (kept where
// FK fails). Angular actuators' positions are deg in the files, rad for the kinematics.
struct SteppedPlatform {
  explicit SteppedPlatform(const Mechanism& m)
      : mechanism(m),
        to_internal(m.actuators_are_angles() ? rad_from_deg(1.0) : 1.0),
        actuators(m.actuator_count()),
        pose(m.home()) {}
  const Pose& at(const std::vector<double>& q) {
    for (int j = 0; j < actuators.size(); ++j) actuators[j] = q[static_cast<std::size_t>(j)] * to_internal;
    if (auto fk = mechanism.forward(actuators, pose)) pose = fk->pose;
    return pose;
  }
  const Mechanism& mechanism;
  double to_internal;
  ActuatorVector actuators;
  Pose pose;
};

}  // namespace

Result<nlohmann::json> interpolate_report(const Machine& machine, const RunFiles& files,
                                          const ReportOptions& options) {
  const fs::path dir(files.directory);
  const std::string steps_file = (dir / "steps.csv").string();
  const std::string contour_file = (dir / "contour.csv").string();
  const nlohmann::json& sm = files.summary;
  const std::string unit = actuator_unit(machine);
  const double step = summary_number(sm, "step_" + unit);
  const double period_s = summary_number(sm, "period_ms") * 1e-3;
  if (!(step > 0.0) || !(period_s > 0.0)) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}/summary.json: step_{} and period_ms must be positive numbers (the summary "
                    "of another machine?)",
                    files.directory, unit));
  }
  auto rows = expected_rows(files.summary, "periods", steps_file);
  if (!rows) return rows.error();
  CsvReader steps, contour;
  if (Status opened = steps.open(steps_file); !opened) return opened.error();
  if (Status opened = contour.open(contour_file); !opened) return opened.error();
  const int n = machine.mechanism->actuator_count();
  auto codes = drive_codes(steps, n);
  if (!codes) return codes.error();
  auto contour_columns = contour_csv_columns(contour);
  if (!contour_columns) return contour_columns.error();
  const std::array<int, 9>& c = *contour_columns;

  const ActuatorLimits limits = limits_in_file_units(machine);
  const double max_step_rate = summary_number(sm, "max_step_rate_hz");
  codes->step = step;
  codes->period_s = period_s;
  codes->max_step_rate = max_step_rate;
  codes->limits = limits;
  const long expected = *rows;
  MinMaxDecimator positions(n, expected, options.chart_buckets),
      step_counts(n, expected, options.chart_buckets), errors(1, expected, options.chart_buckets);
  const double duration = summary_number(sm, "real_time_s");
  SceneBuilder scene(machine, std::isfinite(duration) ? duration : 0.0, expected, options.frames,
                     options.path_points);
  const double rho_max = summary_number(sm, "rho_max_mm");
  if (rho_max > 0.0) scene.set_error_scale(rho_max);

  std::vector<double> srow, crow, q(static_cast<std::size_t>(n)), counts(q.size()), closeness(q.size());
  SteppedPlatform platform(*machine.mechanism);
  long count = 0;
  double t = 0.0, last_frame_time = -1.0;
  int line = 0;
  for (;;) {
    auto more = next_in_step(steps, srow, contour, crow);
    if (!more) return more.error();
    if (!*more) break;
    t = crow[static_cast<std::size_t>(c[0])];
    line = static_cast<int>(crow[static_cast<std::size_t>(c[1])]);
    codes->read(srow, q, counts, closeness);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    positions.add(t, nan, q.data());
    step_counts.add(t, nan, counts.data());
    const double error = crow[static_cast<std::size_t>(c[2])];
    errors.add(t, nan, &error);
    const Eigen::Vector3d executed(crow[static_cast<std::size_t>(c[3])], crow[static_cast<std::size_t>(c[4])],
                                   crow[static_cast<std::size_t>(c[5])]);
    const Eigen::Vector3d programmed(crow[static_cast<std::size_t>(c[6])],
                                     crow[static_cast<std::size_t>(c[7])],
                                     crow[static_cast<std::size_t>(c[8])]);
    scene.add_path_point(programmed, executed.allFinite() ? executed : programmed, error);
    if (scene.frame_due(t)) {
      scene.add_frame(t, line, platform.at(q), closeness);
      last_frame_time = t;
    }
    ++count;
  }
  if (count == 0) return make_error(ErrorCode::bad_input, fmt::format("{}: no periods", steps_file));
  if (t > last_frame_time) {
    scene.add_frame(t, line, platform.at(q), closeness);
  }
  for (auto* d : {&positions, &step_counts, &errors}) d->finish();

  nlohmann::json charts =
      interpolate_charts(positions, step_counts, errors, n, unit, limits, max_step_rate, period_s, rho_max);

  nlohmann::json table = interpolate_table(sm, step, unit, rho_max, files, machine);

  nlohmann::json reached = interpolate_limits_reached(sm, rho_max, max_step_rate, period_s);

  ReportParts parts;
  parts.kind = "interpolate";
  parts.title = fmt::format("{} on {}: {} interpolation", fs::path(files.program).filename().string(),
                            machine.name, sm.value("method", std::string("?")));
  parts.program_file = files.program;
  parts.table = std::move(table);
  parts.limits_reached = std::move(reached);
  parts.summary = files.summary;
  parts.charts = std::move(charts);
  return report_document(machine, std::move(parts), scene);
}

}  // namespace pkm::report
