#include "pipeline/servo_program.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/rotation.hpp"
#include "io/atomic_file.hpp"
#include "io/buffered_file.hpp"
#include "io/json_text.hpp"
#include "io/output_manifest.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "report/report_data.hpp"
#include "report/report_html.hpp"
#include "report/table_rows.hpp"

namespace pkm::pipeline {
namespace fs = std::filesystem;

namespace {

Error servo_table_error(const report::TableRows& table, const std::string& what) {
  Error e = make_error(ErrorCode::bad_input, fmt::format("{}: {}", table.where(), what));
  e.location.file = table.name();
  return e;
}

}  // namespace

bool same_folder(const std::string& a, const std::string& b) {
  std::error_code error;
  return fs::weakly_canonical(fs::absolute(a), error) == fs::weakly_canonical(fs::absolute(b), error);
}

Result<servo::ServoRunInput> read_planned_run(const Machine& machine, const std::string& plan_directory) {
  const Mechanism& mechanism = *machine.mechanism;
  const int m = mechanism.actuator_count();
  const bool angular = mechanism.actuators_are_angles();
  // The plan's tables in the form its folder holds (CSV files or ticks.h5).
  const formats::TickTables tables = report::tick_tables_in(plan_directory);
  auto actuator_table = report::open_tick_table(plan_directory, tables, "actuators");
  if (!actuator_table) return actuator_table.error();
  auto path_table = report::open_tick_table(plan_directory, tables, "path");
  if (!path_table) return path_table.error();
  report::TableRows& actuators = **actuator_table;
  report::TableRows& path = **path_table;
  std::vector<int> q_columns;
  for (int j = 1; j <= m; ++j) {
    auto column = actuators.require(fmt::format("q{}_{}", j, angular ? "deg" : "mm"));
    if (!column) return column.error();
    q_columns.push_back(*column);
  }
  int columns[8];
  const char* names[8] = {"time_s",       "line",      "x_program_mm", "y_program_mm",
                          "z_program_mm", "a_abc_deg", "b_abc_deg",    "c_abc_deg"};
  for (int c = 0; c < 8; ++c) {
    auto column = path.require(names[c]);
    if (!column) return column.error();
    columns[c] = *column;
  }
  auto time_column = actuators.require("time_s");
  if (!time_column) return time_column.error();

  servo::ServoRunInput input;
  const double unit = angular ? std::numbers::pi / 180.0 : 1.0;
  std::vector<double> a, p;
  while (true) {
    auto more = report::next_in_step(actuators, a, path, p);
    if (!more) return more.error();
    if (!*more) break;
    if (std::abs(a[*time_column] - p[columns[0]]) > 1e-6)
      return servo_table_error(path, fmt::format("not the tick of {} (a different run?)", actuators.name()));
    ActuatorVector q(m);
    for (int j = 0; j < m; ++j) q[j] = a[q_columns[j]] * unit;
    for (int c = 0; c < 8; ++c) {
      if (!std::isfinite(p[columns[c]]))
        return servo_table_error(path, fmt::format("{}: not a number", names[c]));
    }
    if (!q.allFinite()) return servo_table_error(actuators, "an actuator position is not a number");
    Pose pose;
    pose.position_mm =
        Eigen::Vector3d(p[columns[2]], p[columns[3]], p[columns[4]]) + machine.motion.program_origin_mm;
    pose.rotation = rotation_from_angles(
        AngleConvention::abc,
        Eigen::Vector3d(p[columns[5]], p[columns[6]], p[columns[7]]) * (std::numbers::pi / 180.0));
    auto complete = mechanism.complete_pose(pose);
    if (!complete) return servo_table_error(path, complete.error().message);
    // To the µs whichever form held it: the servo period is then the CSV's (report/table_rows.hpp).
    const double time_s = report::tick_time_s(a[*time_column]);
    if (!input.time_s.empty() && !(time_s > input.time_s.back()))
      return servo_table_error(actuators, "time_s does not increase");
    input.time_s.push_back(time_s);
    input.line.push_back(static_cast<int>(p[columns[1]]));
    input.setpoint.push_back(q);
    input.pose.push_back(*complete);
  }
  if (input.time_s.size() < 2)
    return make_error(ErrorCode::bad_input, fmt::format("{}: fewer than two servo ticks", actuators.name()));
  input.period_s = input.time_s[1] - input.time_s[0];
  // The plan writes times to the µs: every step must be the same period.
  for (std::size_t k = 1; k < input.time_s.size(); ++k) {
    if (std::abs(input.time_s[k] - input.time_s[k - 1] - input.period_s) > 2e-6) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("{}: row {}: the servo period changes ({} s after {} s)", actuators.name(), k + 1,
                      input.time_s[k] - input.time_s[k - 1], input.period_s));
    }
  }
  input.period_s =
      (input.time_s.back() - input.time_s.front()) / static_cast<double>(input.time_s.size() - 1);
  return input;
}

namespace {

nlohmann::json servo_figures_json(const servo::LoopFigures& f) {
  return {
      {"overshoot_pct", f.step.overshoot_pct},
      {"settling_s", f.step.settling_s},
      {"phase_margin_deg", f.margins.phase_margin_deg},
      {"crossover_hz", f.margins.crossover_hz},
      {"gain_margin_db", std::isfinite(f.margins.gain_margin_db) ? nlohmann::json(f.margins.gain_margin_db)
                                                                 : nlohmann::json(nullptr)}};
}

nlohmann::json servo_summary_json(const Machine& machine, const ServoJob& job, const ServoProgramResult& r) {
  const servo::ServoSummary& s = r.summary;
  const bool angular = machine.mechanism->actuators_are_angles();
  const double shown = angular ? 180.0 / std::numbers::pi : 1.0;  // file units: mm or deg
  nlohmann::json drives = nlohmann::json::array();
  for (int j = 0; j < s.drives; ++j) {
    const servo::ChannelGains& g = r.design.channels[j];
    const servo::DriveServoSummary& d = s.drive[j];
    const servo::ChannelAnalysis& a = r.analysis[j];
    drives.push_back(
        {{"drive", j + 1},
         {"gains",
          {{"position_gain_per_s", g.position_gain_per_s},
           {"speed_gain", g.speed_gain},
           {"speed_integral_s", g.speed_integral_s},
           {"reference_filter_s", g.reference_filter_s},
           {"current_time_constant_s", g.lag_s},
           {"inertia", g.inertia}}},
         // In the file's units: N (N·mm), mm/s (deg/s), N per mm/s (N·mm per deg/s), mm (deg); 0: none.
         {"imperfections",
          {{"friction_coulomb", g.friction_coulomb},
           {"friction_static", g.friction_static},
           {"stribeck_speed", g.stribeck_speed * shown},
           {"friction_viscous", g.friction_viscous / shown},
           {"backlash", g.backlash * shown},
           {"encoder_resolution", g.encoder_resolution * shown},
           {"characteristic_points", g.characteristic_points}}},
         {"speed_loop",
          {{"continuous", servo_figures_json(a.speed_continuous)},
           {"sampled", servo_figures_json(a.speed_sampled)}}},
         {"position_loop",
          {{"continuous", servo_figures_json(a.position_continuous)},
           {"sampled", servo_figures_json(a.position_sampled)}}},
         {"ramp_error_per_speed_s", a.ramp_error_per_speed_s},
         {"max_following_error", d.max_following_error * shown},
         {"rms_following_error", d.rms_following_error * shown},
         {"max_following_line", d.max_following_line},
         {"max_following_time_s", d.max_following_time_s},
         {"peak_force", d.peak_force},
         {"peak_command", d.peak_command},
         {"error_clamps", d.error_clamps},
         {"command_clamps", d.command_clamps},
         {"clamp_lines", d.clamp_lines},
         {"max_coupling_ratio", std::isfinite(d.max_coupling_ratio) ? nlohmann::json(d.max_coupling_ratio)
                                                                    : nlohmann::json(nullptr)},
         {"max_coupling_line", d.max_coupling_line},
         {"coupled_lines", d.coupled_lines}});
  }
  nlohmann::json worst = nlohmann::json::array();
  for (const auto& [line, error] : s.worst_lines)
    worst.push_back({{"line", line}, {"contour_error_mm", error}});
  return {{"kind", "servo"},
          {"pkm_version", std::string(pkm_version())},
          {"machine", machine.source},
          {"plan", job.plan_directory},
          {"tuning", to_string(machine.servo.tuning)},
          {"actuator_unit", angular ? "deg" : "mm"},
          {"force_unit", angular ? "N·mm" : "N"},
          {"period_s", s.period_s},
          {"loop_period_s", s.loop_period_s},
          {"coupled", s.coupled},
          {"sample_delay_periods", r.design.sample_delay_periods},
          {"machine_dynamics", s.has_machine_dynamics},
          {"coupling_ratio_limit", servo::kCouplingRatioLimit},
          {"ticks", s.ticks},
          {"max_contour_error_mm", s.max_contour_error_mm},
          {"rms_contour_error_mm", s.rms_contour_error_mm},
          {"max_contour_line", s.max_contour_line},
          {"max_contour_time_s", s.max_contour_time_s},
          {"max_lag_s", s.max_lag_s},
          {"fk_failures", s.fk_failures},
          {"worst_lines", worst},
          {"drives", drives},
          {"files", {{"ticks", "servo.csv"}, {"bode", "servo_bode.csv"}}}};
}

double servo_db(std::complex<double> value) {
  return 20.0 * std::log10(std::abs(value));
}
double servo_deg(std::complex<double> value) {
  return std::arg(value) * 180.0 / std::numbers::pi;
}

std::string servo_bode_csv(const ServoProgramResult& r, double loop_period_s, int points) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "drive,frequency_hz,speed_open_db,speed_open_deg,speed_closed_db,position_open_db,"
                 "position_open_deg,position_closed_db,speed_open_sampled_db,speed_open_sampled_deg,"
                 "position_open_sampled_db,position_open_sampled_deg,position_closed_sampled_db\n");
  for (int j = 0; j < r.design.drives; ++j) {
    const servo::ChannelGains& g = r.design.channels[j];
    // From a hundredth of the speed loop's corner to ten times the Nyquist frequency of the loop period.
    const double f_max = 10.0 / (2.0 * loop_period_s);
    const double f_min = 0.01 / (2.0 * std::numbers::pi * 4.0 * g.lag_s);
    for (const servo::LoopResponse& p : servo::bode_data(g, loop_period_s, f_min, f_max, points)) {
      fmt::format_to(std::back_inserter(out), "{},{:.6g},{:.4f},{:.3f},{:.4f},{:.4f},{:.3f},{:.4f},", j + 1,
                     p.frequency_hz, servo_db(p.speed_open), servo_deg(p.speed_open),
                     servo_db(p.speed_closed), servo_db(p.position_open), servo_deg(p.position_open),
                     servo_db(p.position_closed));
      if (std::isfinite(p.speed_open_sampled.real())) {
        fmt::format_to(std::back_inserter(out), "{:.4f},{:.3f},{:.4f},{:.3f},{:.4f}\n",
                       servo_db(p.speed_open_sampled), servo_deg(p.speed_open_sampled),
                       servo_db(p.position_open_sampled), servo_deg(p.position_open_sampled),
                       servo_db(p.position_closed_sampled));
      } else {
        fmt::format_to(std::back_inserter(out), ",,,,\n");  // above the Nyquist frequency
      }
    }
  }
  return fmt::to_string(out);
}

// servo.csv's header: per drive the following error, the force and the command, then the tool's errors.
void append_servo_csv_header(fmt::memory_buffer& b, int drives, bool angular) {
  const char* unit = angular ? "deg" : "mm";
  const char* force_unit = angular ? "Nmm" : "N";
  fmt::format_to(std::back_inserter(b), "time_s,line");
  for (int j = 1; j <= drives; ++j) fmt::format_to(std::back_inserter(b), ",e{}_{}", j, unit);
  for (int j = 1; j <= drives; ++j) fmt::format_to(std::back_inserter(b), ",f{}_{}", j, force_unit);
  for (int j = 1; j <= drives; ++j) fmt::format_to(std::back_inserter(b), ",u{}", j);
  fmt::format_to(std::back_inserter(b), ",contour_error_mm,lag_ms,error_clamps,command_clamps\n");
}

// One tick's row; `shown` turns the drives' unit into the file's (rad → deg).
void append_servo_csv_row(fmt::memory_buffer& b, const servo::ServoTick& t, double shown) {
  fmt::format_to(std::back_inserter(b), "{:.6f},{}", t.time_s, t.line);
  for (int j = 0; j < t.drives; ++j)
    fmt::format_to(std::back_inserter(b), ",{:.4e}", ((*t.setpoint)[j] - (*t.position)[j]) * shown);
  for (int j = 0; j < t.drives; ++j) fmt::format_to(std::back_inserter(b), ",{:.4e}", (*t.force)[j]);
  for (int j = 0; j < t.drives; ++j) fmt::format_to(std::back_inserter(b), ",{:.4e}", (*t.command)[j]);
  // Empty where not evaluated (FK failed; the lag where the path stands).
  b.push_back(',');
  if (std::isfinite(t.contour_error_mm)) fmt::format_to(std::back_inserter(b), "{:.4e}", t.contour_error_mm);
  b.push_back(',');
  if (std::isfinite(t.lag_s)) fmt::format_to(std::back_inserter(b), "{:.4f}", t.lag_s * 1e3);
  fmt::format_to(std::back_inserter(b), ",{},{}\n", t.clamps.error, t.clamps.command);
}

// --report: the plan's report with the servo plots, one more member of the output set (written with the
// servo files or not at all), the servo files read back from the staging folder as `pkm report` reads them.
Status stage_servo_report(OutputSet& outputs, const Machine& machine, const ServoJob& job) {
  report_progress(job.progress, "writing the report");
  auto staged = outputs.stage_file(job.report_path);
  if (!staged) return staged.error();
  report::ReportOptions report_options;
  report_options.machine_file = machine.source;
  report_options.servo_directory = outputs.staging_directory();
  auto data = report::report_from_directory(job.plan_directory, report_options);
  if (!data) return data.error();
  return report::write_report_html(*staged, *data);
}

}  // namespace

Result<PlannedServoRun> prepare_planned_servo_run(const Machine& machine, const std::string& plan_directory,
                                                  int inertia_stride, bool coupled,
                                                  const ProgressSink& progress) {
  if (!machine.servo.given()) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: the machine file has no servo: section (the drives' loops; see "
                                  "docs/machine-file.md)",
                                  machine.source));
  }
  report_progress(progress, "reading the plan");
  auto input = read_planned_run(machine, plan_directory);
  if (!input) return input.error();
  // Its files first (a damaged file is named as such), then that they are one plan's and nothing else.
  if (Status checked = check_output_set(plan_directory, {"plan"}); !checked) return checked.error();
  auto steps = servo::loop_steps_per_period(machine, input->period_s);
  if (!steps) return steps.error();
  report_progress(progress, "the drives' inertia along the run");
  auto plant = servo::plant_along_run(machine, *input, inertia_stride);
  if (!plant) return plant.error();
  const int m = machine.mechanism->actuator_count();
  report_progress(progress, "designing the loops");
  auto design = servo::design_loops(machine, plant->inertia.front().diagonal().head(m));
  if (!design) return design.error();
  if (Status stable = servo::check_stability(machine, *design, *plant, *input, *steps, {coupled}); !stable)
    return stable.error();
  return PlannedServoRun{std::move(*input), *steps, std::move(*plant), std::move(*design)};
}

Result<ServoProgramResult> servo_program(const Machine& machine, const ServoJob& job) {
  auto prepared =
      prepare_planned_servo_run(machine, job.plan_directory, job.inertia_stride, job.coupled, job.progress);
  if (!prepared) return prepared.error();
  const servo::ServoRunInput* input = &prepared->input;
  const int* steps = &prepared->steps_per_period;
  const servo::ServoPlant* plant = &prepared->plant;
  const servo::LoopDesign* design = &prepared->design;
  const int m = machine.mechanism->actuator_count();

  ServoProgramResult result;
  result.design = *design;
  const double loop_period_s = input->period_s / *steps;
  for (int j = 0; j < m; ++j)
    result.analysis.push_back(servo::analyse_channel(design->channels[j], loop_period_s));

  // Without --out (or with the plan's own folder) the servo files join the plan's set beside its files, where
  // pkm report finds them; elsewhere they are a set of their own.
  OutputSet outputs{"servo"};
  if (job.out_directory.empty() || same_folder(job.out_directory, job.plan_directory)) {
    if (Status joined = outputs.join_directory(job.plan_directory, {"plan"}); !joined) return joined.error();
  } else if (Status used = outputs.use_directory(job.out_directory); !used) {
    return used.error();
  }
  BufferedStagedFile ticks_csv;
  if (Status opened = ticks_csv.open(outputs.staged_path("servo.csv")); !opened) return opened.error();
  const bool angular = machine.mechanism->actuators_are_angles();
  const double shown = angular ? 180.0 / std::numbers::pi : 1.0;
  append_servo_csv_header(ticks_csv.buffer, m, angular);
  const double run_s = input->time_s.empty() ? 0.0 : input->time_s.back();
  long ticks_done = 0;
  auto summary = servo::run_servo(
      machine, *design, *plant, *input, *steps, {job.coupled}, [&](const servo::ServoTick& t) -> Status {
        if (ticks_done++ % 4096 == 0 && run_s > 0.0)
          report_progress(job.progress, "running the servo loops", t.time_s / run_s, t.line);
        append_servo_csv_row(ticks_csv.buffer, t, shown);
        if (job.listener) {
          if (Status told = job.listener(t); !told) return told;
        }
        return ticks_csv.flush_if_large();
      });
  if (!summary) return summary.error();
  result.summary = *summary;
  if (Status committed = ticks_csv.commit(); !committed) return committed.error();
  if (Status written = write_file_atomically(outputs.staged_path("servo_bode.csv"),
                                             servo_bode_csv(result, loop_period_s, job.bode_points));
      !written)
    return written.error();
  result.json = servo_summary_json(machine, job, result);
  if (Status written =
          write_file_atomically(outputs.staged_path("servo_summary.json"), json_text(result.json) + "\n");
      !written)
    return written.error();
  if (!job.report_path.empty()) {
    if (Status written = stage_servo_report(outputs, machine, job); !written) return written.error();
  }
  if (Status committed = outputs.commit(); !committed) return committed.error();
  return result;
}

}  // namespace pkm::pipeline
