// The report of a `pkm plan` run: actuator positions, speeds and accelerations against their limits, path
// speed against the programmed feed, the path error, and the 3-D animation, from the actuators and path
// tables (actuators.csv and path.csv, or their groups of ticks.h5: report/table_rows.hpp); with --dynamics
// also the drive forces, power and energy (forces) and the dynamic tool error (response), and struts that can
// be coloured by force; after `pkm servo` the following and contour error, the servo rows of the table and
// the loops' Bode data (servo_plots.hpp).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "report/dynamics_table.hpp"
#include "report/dynamics_trace.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"
#include "report/servo_plots.hpp"
#include "report/simulate_plots.hpp"
#include "report/table_rows.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

/// The largest ratio of something to its limit over the run, and where it happened.
struct LimitPeak {
  double ratio = 0.0;
  double value = 0.0;
  double limit = 0.0;
  int actuator = 0;
  int line = 0;
  double time_s = 0.0;
  void offer(double r, double v, double lim, int j, int at_line, double t) {
    if (r > ratio) *this = LimitPeak{r, v, lim, j, at_line, t};
  }
};

double value_or_nan(const nlohmann::json& summary, const char* key) {
  return summary.contains(key) && summary[key].is_number() ? summary[key].get<double>()
                                                           : std::numeric_limits<double>::quiet_NaN();
}

int line_of(const nlohmann::json& summary, const char* key) {
  return summary.contains(key) && summary[key].is_number_integer() ? summary[key].get<int>() : 0;
}

/// A limit the run comes within 1 % of is "reached"; beyond it (more than rounding) "exceeded".
void add_limit_entry(nlohmann::json& reached, const LimitPeak& peak, const std::string& what,
                     const std::string& unit) {
  if (peak.ratio < 0.99) return;
  const std::string how = what == "position" ? fmt::format("at its limit {:.6g} {}", peak.limit, unit)
                                             : fmt::format("{:.1f} % of the limit {:.6g} {}",
                                                           100.0 * peak.ratio, peak.limit, unit);
  reached.push_back(
      {{"what", fmt::format("actuator {} {} {:.6g} {} ({})", peak.actuator + 1, what, peak.value, unit, how)},
       {"line", peak.line},
       {"time_s", peak.time_s},
       {"severity", peak.ratio > 1.0 + 1e-3 ? "exceeded" : "reached"}});
}

// Each drive's position, speed and acceleration tick by tick (the latter two by differences), and the peaks
// of speed, acceleration and position against their limits; how close each drive is to its limits is only
// formed for the scene's frames (closeness_now), not at every tick.
struct ActuatorTrack {
  ActuatorTrack(int drives, const ActuatorLimits& limits)
      : limits_(limits),
        q(static_cast<std::size_t>(drives)),
        q_prev(q.size()),
        v(q.size()),
        v_prev(q.size()),
        a(q.size()),
        closeness(q.size()) {}

  void add(const std::vector<double>& row, double dt, long count, int line, double t) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t j = 0; j < q.size(); ++j) {
      q[j] = row[j + 1];
      v[j] = count > 0 && dt > 0.0 ? (q[j] - q_prev[j]) / dt : nan;
      a[j] = count > 1 && dt > 0.0 ? (v[j] - v_prev[j]) / dt : nan;
    }
    // Every drive has the same limits, so the largest ratio is the largest value: the ratio is only formed
    // for a new peak.
    for (std::size_t j = 0; j < q.size(); ++j) {
      const int drive = static_cast<int>(j);
      if (limits_.speed && std::abs(v[j]) > speed_peak.value)
        speed_peak.offer(std::abs(v[j]) / *limits_.speed, std::abs(v[j]), *limits_.speed, drive, line, t);
      if (limits_.accel && std::abs(a[j]) > accel_peak.value)
        accel_peak.offer(std::abs(a[j]) / *limits_.accel, std::abs(a[j]), *limits_.accel, drive, line, t);
      if (limits_.min && limits_.max && *limits_.max > *limits_.min) {
        if (q[j] > highest_q) highest_q = q[j], highest_at = {drive, line, t};
        if (q[j] < lowest_q) lowest_q = q[j], lowest_at = {drive, line, t};
      }
    }
  }
  void step() {
    q_prev = q;
    v_prev = v;
  }
  /// How close each drive is to its limits at the last tick added (0 far, 1 at a limit).
  const std::vector<double>& closeness_now() {
    for (std::size_t j = 0; j < q.size(); ++j) closeness[j] = limit_closeness(limits_, q[j], v[j], a[j]);
    return closeness;
  }
  /// The position nearest either end of the range, as a ratio: 1 at the end, 0.99 within 1 % of the range
  /// from it (on a tie, the end that was come nearest first).
  LimitPeak position_peak() const {
    LimitPeak peak;
    if (!(limits_.min && limits_.max && *limits_.max > *limits_.min)) return peak;
    const double range = *limits_.max - *limits_.min;
    auto offer_low = [&] {
      peak.offer(1.0 + (*limits_.min - lowest_q) / range, lowest_q, *limits_.min, lowest_at.drive,
                 lowest_at.line, lowest_at.time_s);
    };
    auto offer_high = [&] {
      peak.offer(1.0 + (highest_q - *limits_.max) / range, highest_q, *limits_.max, highest_at.drive,
                 highest_at.line, highest_at.time_s);
    };
    if (lowest_at.time_s < highest_at.time_s) {
      offer_low();
      offer_high();
    } else {
      offer_high();
      offer_low();
    }
    return peak;
  }

  ActuatorLimits limits_;
  std::vector<double> q, q_prev, v, v_prev, a, closeness;
  LimitPeak speed_peak, accel_peak;

 private:
  struct Where {
    int drive = 0, line = 0;
    double time_s = 0.0;
  };
  double highest_q = -std::numeric_limits<double>::infinity(),
         lowest_q = std::numeric_limits<double>::infinity();
  Where highest_at, lowest_at;
};

// The columns of the path table the report reads, in kPathColumns' order; feed and path error are -1 when
// absent.
constexpr std::size_t kFeedColumn = 10, kPathErrorColumn = 11;
Result<std::array<int, 12>> path_table_columns(const TableRows& path) {
  // The pose in program coordinates: the tool point from program zero and G-code's A B C (plan_output.cpp).
  static const char* const kPathColumns[] = {"time_s",       "line",           "s",         "x_program_mm",
                                             "y_program_mm", "z_program_mm",   "a_abc_deg", "b_abc_deg",
                                             "c_abc_deg",    "path_speed_mm_s"};
  std::array<int, 12> column{};
  for (std::size_t k = 0; k < 10; ++k) {
    auto index = path.require(kPathColumns[k]);
    if (!index) return index.error();
    column[k] = *index;
  }
  column[kFeedColumn] = path.column("feed_mm_s");  // older runs lack these two columns
  column[kPathErrorColumn] = path.column("path_error_mm");
  return column;
}

// The plan's own plots, decimated: each drive's position q, speed v and acceleration a (named so that a
// legend tells the three plots apart), the path speed with the programmed feed, and the path error.
struct PlanCharts {
  PlanCharts(int drives, long expected, int buckets)
      : positions(drives, expected, buckets),
        speeds(drives, expected, buckets),
        accels(drives, expected, buckets),
        path_speed(2, expected, buckets),
        path_error(1, expected, buckets) {}
  void finish_all() {
    for (auto* d : {&positions, &speeds, &accels, &path_speed, &path_error}) d->finish();
  }
  nlohmann::json json(int n, const std::string& unit, const ActuatorLimits& limits, bool with_error) const {
    nlohmann::json charts = nlohmann::json::array();
    charts.push_back(chart_json("actuator_positions", "Actuator positions", "position", unit, positions,
                                actuator_names(n), true, travel_limit_lines(limits, unit)));
    charts.push_back(chart_json("actuator_speeds", "Actuator speeds", "speed", unit + "/s", speeds,
                                drive_names("v", n), true, plus_minus_lines(limits.speed, unit + "/s")));
    charts.push_back(chart_json("actuator_accels", "Actuator accelerations", "acceleration", unit + "/s²",
                                accels, drive_names("a", n), true,
                                plus_minus_lines(limits.accel, unit + "/s²")));
    charts.push_back(chart_json("path_speed", "Path speed and programmed feed", "speed", "mm/s", path_speed,
                                {"path speed", "programmed feed × override"}, true));
    if (with_error) {
      charts.push_back(chart_json("contour_error", "Path error (tool from the programmed path, mid-period)",
                                  "error", "mm", path_error, {"path error"}, true));
    }
    return charts;
  }
  MinMaxDecimator positions, speeds, accels, path_speed, path_error;
};

// The summary table of a plan run, from its summary.json.
nlohmann::json plan_table(const nlohmann::json& sm, const std::string& u) {
  nlohmann::json table = nlohmann::json::array();
  table.push_back(table_row("Duration", with_unit(value_or_nan(sm, "duration_s"), "s")));
  table.push_back(table_row(
      "Blocks / path length",
      fmt::format("{} / {}", sm.value("blocks", 0), with_unit(value_or_nan(sm, "path_length_mm"), "mm"))));
  table.push_back(table_row("Servo rate / override",
                            fmt::format("{} / {} %", with_unit(value_or_nan(sm, "rate_hz"), "Hz"),
                                        value_or_nan(sm, "override_pct"))));
  const std::string speed_key = "max_actuator_speed_" + u + "_s",
                    accel_key = "max_actuator_accel_" + u + "_s2";
  table.push_back(table_row("Max actuator speed", with_unit(value_or_nan(sm, speed_key.c_str()), u + "/s"),
                            line_of(sm, "max_actuator_speed_line")));
  table.push_back(table_row("Max actuator acceleration",
                            with_unit(value_or_nan(sm, accel_key.c_str()), u + "/s²"),
                            line_of(sm, "max_actuator_accel_line")));
  table.push_back(table_row("Max path error", with_unit(value_or_nan(sm, "max_path_error_mm"), "mm"),
                            line_of(sm, "max_path_error_line")));
  table.push_back(
      table_row("Max orientation error", with_unit(value_or_nan(sm, "max_orientation_error_deg"), "°")));
  table.push_back(
      table_row("Max path speed / of the feed",
                fmt::format("{} / {:.1f} %", with_unit(value_or_nan(sm, "max_path_speed_mm_s"), "mm/s"),
                            100.0 * value_or_nan(sm, "max_feed_ratio"))));
  table.push_back(table_row("Max condition number", with_unit(value_or_nan(sm, "max_condition_number"), "")));
  table.push_back(table_row("Time limited by the actuators",
                            fmt::format("{:.1f} %", 100.0 * value_or_nan(sm, "actuator_limited_fraction"))));
  for (auto& row : dynamics_table_rows(sm)) table.push_back(std::move(row));
  return table;
}

}  // namespace

std::string with_unit(double value, const std::string& unit) {
  if (!std::isfinite(value)) return "—";
  return unit.empty() ? fmt::format("{:.6g}", value) : fmt::format("{:.6g} {}", value, unit);
}

namespace {

// The document of a plan run: its charts with the analyses', the table, the limits reached and the scene.
Result<nlohmann::json> plan_document(const Machine& machine, const RunFiles& files, const std::string& unit,
                                     nlohmann::json charts, const ActuatorTrack& track,
                                     DynamicsTrace& dynamics, ServoTrace& servo,
                                     const SimulateTrace& simulate, SceneBuilder& scene) {
  // The force limit is in N; angular drives give N·mm, so no line is drawn for them.
  const std::optional<double> force_limit =
      machine.mechanism->actuators_are_angles() ? std::nullopt : machine.limits.force_N;
  for (auto& chart : dynamics.charts(force_limit)) charts.push_back(std::move(chart));
  for (auto& chart : servo.charts(machine)) charts.push_back(std::move(chart));
  for (auto& chart : simulate.charts()) charts.push_back(std::move(chart));

  const nlohmann::json& sm = files.summary;
  const std::string u = unit;
  nlohmann::json table = plan_table(sm, u);
  for (auto& row : servo.table_rows()) table.push_back(std::move(row));
  for (auto& row : simulate.table_rows()) table.push_back(std::move(row));
  table.push_back(table_row("Program", files.program));
  table.push_back(table_row("Machine file", machine.source));

  nlohmann::json reached = nlohmann::json::array();
  add_limit_entry(reached, track.speed_peak, "speed", u + "/s");
  add_limit_entry(reached, track.accel_peak, "acceleration", u + "/s²");
  add_limit_entry(reached, track.position_peak(), "position", u);
  for (auto& entry : dynamics_limit_entries(sm, force_limit)) reached.push_back(std::move(entry));
  for (auto& entry : servo.limit_entries()) reached.push_back(std::move(entry));

  ReportParts parts;
  parts.kind = "plan";
  parts.title = fmt::format("{} on {}", fs::path(files.program).filename().string(), machine.name);
  parts.program_file = files.program;
  parts.table = std::move(table);
  parts.limits_reached = std::move(reached);
  parts.warnings = servo.warnings();
  parts.summary = files.summary;
  parts.charts = std::move(charts);
  nlohmann::json report = report_document(machine, std::move(parts), scene);
  if (servo.active()) {
    auto object = servo.object();
    if (!object) return object.error();
    report["servo"] = std::move(*object);
  }
  return report;
}

// The run's actuators and path tables, in the form its folder holds, with the path's columns and the rows
// expected (the summary's ticks, else counted).
struct PlanTables {
  formats::TickTables form = formats::TickTables::csv;
  std::unique_ptr<TableRows> path, actuators;
  std::array<int, 12> column{};
  long expected = 0;
};

Result<PlanTables> open_plan_tables(const Machine& machine, const RunFiles& files) {
  PlanTables t;
  t.form = tick_tables_in(files.directory);
  auto path = open_tick_table(files.directory, t.form, "path");
  if (!path) return path.error();
  auto actuators = open_tick_table(files.directory, t.form, "actuators");
  if (!actuators) return actuators.error();
  t.path = std::move(*path);
  t.actuators = std::move(*actuators);
  const nlohmann::json& sm = files.summary;
  const bool counted = sm.contains("ticks") && sm["ticks"].is_number_integer() && sm["ticks"].get<long>() > 0;
  auto rows = counted ? Result<long>(sm["ticks"].get<long>()) : t.path->count_rows();
  if (!rows) return rows.error();
  t.expected = *rows;
  const int n = machine.mechanism->actuator_count();
  if (static_cast<int>(t.actuators->columns().size()) != n + 1) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: {} actuator columns, but {} has {} actuators", t.actuators->where(),
                                  t.actuators->columns().size() - 1, machine.source, n));
  }
  auto columns = path_table_columns(*t.path);
  if (!columns) return columns.error();
  t.column = *columns;
  return t;
}

}  // namespace

Result<nlohmann::json> plan_report(const Machine& machine, const RunFiles& files,
                                   const ReportOptions& options) {
  auto opened_tables = open_plan_tables(machine, files);
  if (!opened_tables) return opened_tables.error();
  TableRows& path = *opened_tables->path;
  TableRows& actuators = *opened_tables->actuators;
  const std::array<int, 12>& column = opened_tables->column;
  const formats::TickTables tables = opened_tables->form;
  const int n = machine.mechanism->actuator_count();

  const std::string unit = actuator_unit(machine);
  const ActuatorLimits limits = limits_in_file_units(machine);
  const long expected = opened_tables->expected;
  PlanCharts plots(n, expected, options.chart_buckets);
  const double duration = value_or_nan(files.summary, "duration_s");
  SceneBuilder scene(machine, std::isfinite(duration) ? duration : 0.0, expected, options.frames,
                     options.path_points);
  DynamicsTrace dynamics;
  if (Status opened =
          dynamics.open(files.directory, tables, files.summary, n, expected, options.chart_buckets);
      !opened)
    return opened.error();
  ServoTrace servo;
  if (Status opened = servo.open(files.directory, options.servo_directory, files.summary, n, expected,
                                 options.chart_buckets);
      !opened)
    return opened.error();
  SimulateTrace simulate;
  if (Status opened =
          simulate.open(options.simulate_directory.empty() ? files.directory : options.simulate_directory,
                        files.summary, expected, options.chart_buckets);
      !opened)
    return opened.error();

  std::vector<double> prow, arow;
  ActuatorTrack track(n, limits);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  long count = 0;
  double t_prev = 0.0, last_frame_time = -1.0;
  Pose pose;
  Eigen::Vector3d abc_deg = Eigen::Vector3d::Zero();
  int line = 0;
  double t = 0.0;
  for (;;) {
    auto more = next_in_step(path, prow, actuators, arow);
    if (!more) return more.error();
    if (!*more) break;
    t = tick_time_s(prow[static_cast<std::size_t>(column[0])]);
    line = static_cast<int>(prow[static_cast<std::size_t>(column[1])]);
    const double s = prow[static_cast<std::size_t>(column[2])];
    track.add(arow, t - t_prev, count, line, t);
    plots.positions.add(t, s, track.q.data());
    plots.speeds.add(t, s, track.v.data());
    plots.accels.add(t, s, track.a.data());
    const double feed = column[kFeedColumn] >= 0 ? prow[static_cast<std::size_t>(column[kFeedColumn])] : nan;
    const double speed_feed[2] = {prow[static_cast<std::size_t>(column[9])], feed};
    plots.path_speed.add(t, s, speed_feed);
    const double error =
        column[kPathErrorColumn] >= 0 ? prow[static_cast<std::size_t>(column[kPathErrorColumn])] : nan;
    plots.path_error.add(t, s, &error);
    if (Status read = dynamics.next(t, s); !read) return read.error();
    if (Status read = servo.next(t, s); !read) return read.error();
    if (Status read = simulate.next(t, s); !read) return read.error();

    pose.position_mm =
        Eigen::Vector3d(prow[static_cast<std::size_t>(column[3])], prow[static_cast<std::size_t>(column[4])],
                        prow[static_cast<std::size_t>(column[5])]) +
        machine.motion.program_origin_mm;
    abc_deg =
        Eigen::Vector3d(prow[static_cast<std::size_t>(column[6])], prow[static_cast<std::size_t>(column[7])],
                        prow[static_cast<std::size_t>(column[8])]);
    // The tool is where the drives put it at every tick; between ticks it deviates by the path error.
    scene.add_path_point(pose.position_mm, pose.position_mm, error);
    if (scene.frame_due(t)) {
      // The orientation only matters for the frames (a rotation per tick would cost as much as the parsing).
      pose.rotation = rotation_from_angles(AngleConvention::abc, abc_deg * rad_from_deg(1.0));
      scene.add_frame(t, line, pose, track.closeness_now());
      if (dynamics.active()) scene.add_frame_forces(dynamics.forces());
      last_frame_time = t;
    }
    track.step();
    t_prev = t;
    ++count;
  }
  if (count == 0) return make_error(ErrorCode::bad_input, fmt::format("{}: no rows", path.name()));
  if (t > last_frame_time) {  // the end of the run is a frame
    pose.rotation = rotation_from_angles(AngleConvention::abc, abc_deg * rad_from_deg(1.0));
    scene.add_frame(t, line, pose, track.closeness_now());
    if (dynamics.active()) scene.add_frame_forces(dynamics.forces());
  }
  if (Status finished = dynamics.finish(); !finished) return finished.error();
  if (Status finished = servo.finish(); !finished) return finished.error();
  if (Status finished = simulate.finish(); !finished) return finished.error();
  scene.set_force_scale(dynamics.peak_force(), dynamics.force_unit());
  plots.finish_all();
  nlohmann::json charts = plots.json(n, unit, limits, column[kPathErrorColumn] >= 0);

  return plan_document(machine, files, unit, std::move(charts), track, dynamics, servo, simulate, scene);
}

}  // namespace pkm::report
