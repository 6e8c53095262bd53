#include "formats/plan_files.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "io/json_text.hpp"
#include "io/version.hpp"
#include "planning/machine_warnings.hpp"
#include "planning/run_accuracy.hpp"

namespace pkm::formats {

namespace {
nlohmann::json dynamics_json(const dynamics::RunDynamicsSummary& d, bool angular) {
  const std::string unit = angular ? "Nmm" : "N";
  nlohmann::json drives = nlohmann::json::array();
  for (int j = 0; j < d.drives; ++j) {
    drives.push_back({{"peak_force_" + unit, d.peak_force_N[j]},
                      {"peak_force_line", d.peak_force_line[j]},
                      {"peak_force_time_s", d.peak_force_time_s[j]},
                      {"peak_static_" + unit, d.peak_static_N[j]},
                      {"peak_dynamic_" + unit, d.peak_dynamic_N[j]},
                      {"peak_power_W", d.peak_power_W[j]}});
  }
  return {{"model", "rigid"},
          {"drives", drives},
          {"peak_total_power_W", d.peak_total_power_W},
          {"peak_total_power_line", d.peak_total_power_line},
          {"energy_no_recovery_J", d.energy.no_recovery_J},
          {"energy_braking_free_J", d.energy.braking_free_J},
          {"energy_recovery_J", d.energy.recovery_J}};
}

}  // namespace

nlohmann::json plan_summary_json(const planning::MotionPlan& plan, const Machine& machine,
                                 const analyses::PlanRun& plan_run) {
  const planning::RunSummary& run = plan_run.motion;
  const bool angular = machine.mechanism->actuators_are_angles();
  const double scale = angular ? deg_from_rad(1.0) : 1.0;
  const int n = machine.mechanism->actuator_count();
  nlohmann::json actuators = nlohmann::json::array();
  for (int j = 0; j < n; ++j) {
    actuators.push_back({{"max_speed", run.max_speed[j] * scale},
                         {"max_accel", run.max_accel[j] * scale},
                         {"min_position", run.min_position[j] * scale},
                         {"max_position", run.max_position[j] * scale},
                         {"reversals", run.reversals[j]}});
  }
  const std::string unit = angular ? "deg" : "mm";
  nlohmann::json limits = nlohmann::json::object();
  if (machine.limits.speed) limits["actuator_speed"] = *machine.limits.speed * scale;
  if (machine.limits.accel) limits["actuator_accel"] = *machine.limits.accel * scale;
  if (machine.limits.min) limits["actuator_min"] = *machine.limits.min * scale;
  if (machine.limits.max) limits["actuator_max"] = *machine.limits.max * scale;
  const planning::PlanStatistics& st = plan.statistics;
  nlohmann::json summary = {
      {"program", plan.program_source},
      {"machine", machine.source},
      {"pkm_version", std::string(pkm_version())},
      {"duration_s", run.duration_s},
      {"ticks", run.ticks},
      {"rate_hz", run.rate_hz},
      {"override_pct", run.override_pct},
      {"blocks", st.blocks},
      {"segments", st.segments},
      {"blends", st.blends},
      {"path_length_mm", st.length_mm},
      {"actuator_unit", unit},
      {"max_actuator_speed_" + unit + "_s", run.max_actuator_speed * scale},
      {"max_actuator_accel_" + unit + "_s2", run.max_actuator_accel * scale},
      {"max_actuator_speed_line", run.max_speed_line},
      {"max_actuator_accel_line", run.max_accel_line},
      {"max_path_error_mm", run.max_path_error_mm},
      {"max_path_error_line", run.max_path_error_line},
      {"path_error_bound_mm", planning::path_error_bound_mm(plan)},
      {"max_orientation_error_deg", run.max_orientation_error_deg},
      {"max_path_speed_mm_s", run.max_path_speed},
      {"max_feed_ratio", run.max_feed_ratio},
      {"max_path_accel_mm_s2", run.max_path_accel},
      {"max_path_jerk_mm_s3", run.max_path_jerk},
      {"jerk_filter_s", st.filter_time_s},
      {"max_condition_number", st.max_condition_number},
      {"actuator_limited_fraction", st.actuator_limited_fraction},
      {"planning_samples", st.samples},
      {"lookahead_binding", st.lookahead_binding},
      {"limits", limits},
      {"actuators", actuators},
      {"warnings", planning::machine_warnings(machine)},
  };
  if (st.lookahead_binding > 0) {
    summary["warnings"].push_back(fmt::format(
        "the look-ahead window set the speed at {} places (it was full before the braking distance was "
        "found): the motion is slower there than the whole program's plan; raise --lookahead-mm or "
        "--lookahead-moves",
        st.lookahead_binding));
  }
  if (!run.path_error_evaluated) {  // not measured (--no-path-error): no figure rather than a 0 that claims
    for (const char* key :
         {"max_path_error_mm", "max_path_error_line", "path_error_bound_mm", "max_orientation_error_deg"})
      summary[key] = nullptr;
  }
  if (plan_run.dynamics) summary["dynamics"] = dynamics_json(*plan_run.dynamics, angular);
  if (plan_run.elastic) {
    nlohmann::json& d = summary["dynamics"];
    d["lowest_natural_frequency_Hz"] = plan_run.elastic->lowest_frequency_Hz;
    d["static_deflection_at_start_mm"] = plan_run.elastic->start_deflection_mm;
    d["max_dynamic_tool_error_mm"] = plan_run.elastic->max_tool_error_mm;
    d["max_dynamic_tool_error_line"] = plan_run.elastic->max_tool_error_line;
    d["max_dynamic_tool_error_time_s"] = plan_run.elastic->max_tool_error_time_s;
    d["max_dynamic_rotation_deg"] = plan_run.elastic->max_rotation_deg;
  }
  if (plan_run.deflection) {
    const stiffness::DeflectionSummary& f = *plan_run.deflection;
    summary["stiffness"] = {{"model", std::string(stiffness::to_string(f.model))},
                            {"max_normal_deflection_mm", f.max_normal_mm},
                            {"max_normal_deflection_line", f.max_normal_line},
                            {"max_normal_deflection_time_s", f.max_normal_time_s},
                            {"rms_normal_deflection_mm", f.rms_normal_mm},
                            {"max_deflection_mm", f.max_deflection_mm},
                            {"max_deflection_line", f.max_deflection_line},
                            {"max_strut_force_N", f.max_strut_force_N},
                            {"max_strut_force_strut", f.max_strut_force_strut},
                            {"max_strut_force_line", f.max_strut_force_line}};
  }
  return summary;
}

namespace {

// One row of path.csv: the tool point in program coordinates, A B C, speed, feed cap and path error (the
// values of path_values).
void write_path_row(const double* v, fmt::memory_buffer& path_csv) {
  fmt::format_to(std::back_inserter(path_csv),
                 "{:.6f},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4f},{:.4f},", v[0],
                 static_cast<long>(v[1]), v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10]);
  // An empty field where the error was not evaluated (first tick, --no-path-error, FK failure).
  if (std::isfinite(v[11])) fmt::format_to(std::back_inserter(path_csv), "{:.3e}", v[11]);
  path_csv.push_back('\n');
}

}  // namespace

const Eigen::Vector3d& AbcOfRotation::of(const Eigen::Matrix3d& rotation) {
  // Bit for bit: −0 and +0 compare equal but give atan2 different angles (±180°). NaN at first.
  if (std::memcmp(rotation.data(), rotation_.data(), sizeof(double) * 9) != 0) {
    rotation_ = rotation;
    abc_deg_ = angles_from_rotation(AngleConvention::abc, rotation) * deg_from_rad(1.0);
  }
  return abc_deg_;
}

void path_values(const planning::ServoTick& tick, const planning::RunMonitor& monitor, const Machine& machine,
                 AbcOfRotation& angles, double* out) {
  const Eigen::Vector3d p = tick.pose.position_mm - machine.motion.program_origin_mm;
  const Eigen::Vector3d& abc = angles.of(tick.pose.rotation);
  const double e = monitor.last_path_error_mm();
  const double values[12] = {tick.time_s,
                             static_cast<double>(tick.line),
                             tick.s,
                             p.x(),
                             p.y(),
                             p.z(),
                             abc.x(),
                             abc.y(),
                             abc.z(),
                             tick.path_speed,
                             monitor.last_feed_cap(),
                             std::isfinite(e) ? e : std::nan("")};
  std::copy(values, values + 12, out);
}

PlanFiles::PlanFiles(const Machine& machine, const analyses::PlanAnalysisOptions& analyses, TickTables tables)
    : machine_(machine),
      analyses_(analyses),
      tables_(tables),
      actuators_(machine.mechanism->actuator_count()),
      angular_(machine.mechanism->actuators_are_angles()),
      commands_(machine.dynamics.drive != DriveModel::ideal) {}

Status PlanFiles::open(OutputSet& outputs) {
  if (tables_ == TickTables::hdf5) return open_hdf5(outputs);
  const bool elastic = analyses_.dynamics && analyses_.elastic;
  const std::vector<Hdf5Column> none;
  for (auto [file, name, columns, wanted] :
       {std::tuple{&actuators_csv_, "actuators.csv", actuator_columns(actuators_, angular_), true},
        std::tuple{&path_csv_, "path.csv", path_columns(), true},
        std::tuple{&summary_file_, "summary.json", none, true},
        std::tuple{&forces_csv_, "forces.csv", force_columns(actuators_, angular_, commands_),
                   analyses_.dynamics},
        std::tuple{&response_csv_, "response.csv", response_columns(), elastic},
        std::tuple{&deflection_csv_, "deflection.csv", deflection_columns(), analyses_.stiffness}}) {
    if (!wanted) continue;
    if (Status opened = file->open(outputs.staged_path(name)); !opened) return opened;
    if (!columns.empty()) fmt::format_to(std::back_inserter(file->buffer), "{}", csv_header(columns));
  }
  return ok_status();
}

Status PlanFiles::on_tick(const planning::ServoTick& tick, const planning::RunMonitor& monitor) {
  if (tables_ == TickTables::hdf5) return on_tick_hdf5(tick, monitor);
  auto& a = actuators_csv_.buffer;
  const double scale = angular_ ? deg_from_rad(1.0) : 1.0;
  fmt::format_to(std::back_inserter(a), "{:.6f}", tick.time_s);
  for (int j = 0; j < actuators_; ++j)
    fmt::format_to(std::back_inserter(a), ",{:.6f}", tick.actuators[j] * scale);
  a.push_back('\n');
  double path[kPathColumns];
  path_values(tick, monitor, machine_, abc_, path);
  write_path_row(path, path_csv_.buffer);
  for (BufferedStagedFile* f : {&actuators_csv_, &path_csv_}) {
    if (auto flushed = f->flush_if_large(); !flushed) return flushed;
  }
  return ok_status();
}

analyses::PlanAnalysisSinks PlanFiles::analysis_sinks() {
  if (tables_ == TickTables::hdf5) return hdf5_sinks();
  analyses::PlanAnalysisSinks sinks;
  const int n = actuators_;
  const bool commands = commands_;
  if (analyses_.dynamics) {
    sinks.dynamics = [this, n, commands](const dynamics::TickDynamics& t) -> Status {
      auto& b = forces_csv_.buffer;
      fmt::format_to(std::back_inserter(b), "{:.6f},{}", t.time_s, t.line);
      for (int j = 0; j < n; ++j) {
        fmt::format_to(std::back_inserter(b), ",{:.4f},{:.4f},{:.4f}", t.forces.total[j],
                       t.forces.static_part[j], t.forces.dynamic_part[j]);
      }
      for (int j = 0; j < n; ++j) fmt::format_to(std::back_inserter(b), ",{:.5f}", t.power_W[j]);
      for (int j = 0; j < n && commands; ++j)
        fmt::format_to(std::back_inserter(b), ",{:.4f}", t.command_N[j]);
      b.push_back('\n');
      return forces_csv_.flush_if_large();
    };
  }
  if (analyses_.dynamics && analyses_.elastic) {
    sinks.elastic = [this](const dynamics::ElasticTick& t) -> Status {
      fmt::format_to(std::back_inserter(response_csv_.buffer),
                     "{:.6f},{},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e}\n", t.time_s, t.line, t.deviation_mm.x(),
                     t.deviation_mm.y(), t.deviation_mm.z(), t.rotation_deg, t.tool_error_mm);
      return response_csv_.flush_if_large();
    };
  }
  if (analyses_.stiffness) {
    sinks.deflection = [this](const stiffness::DeflectionTick& t) -> Status {
      fmt::format_to(std::back_inserter(deflection_csv_.buffer),
                     "{:.6f},{},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e}\n", t.time_s, t.line, t.deflection_mm.x(),
                     t.deflection_mm.y(), t.deflection_mm.z(), t.normal_mm, t.rotation_rad);
      return deflection_csv_.flush_if_large();
    };
  }
  return sinks;
}

Status PlanFiles::finish(const nlohmann::json& summary) {
  fmt::format_to(std::back_inserter(summary_file_.buffer), "{}\n", json_text(summary));
  if (Status committed = summary_file_.commit(); !committed) return committed;
  if (tables_ == TickTables::hdf5) return finish_hdf5();
  const bool elastic = analyses_.dynamics && analyses_.elastic;
  for (auto [file, written] :
       {std::pair{&forces_csv_, analyses_.dynamics}, std::pair{&response_csv_, elastic},
        std::pair{&deflection_csv_, analyses_.stiffness}}) {
    if (!written) continue;
    if (auto committed = file->commit(); !committed) return committed;
  }
  for (BufferedStagedFile* f : {&actuators_csv_, &path_csv_}) {
    if (auto committed = f->commit(); !committed) return committed;
  }
  return ok_status();
}

}  // namespace pkm::formats
