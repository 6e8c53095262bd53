// The report of a `pkm stiffness` run (points.csv, summary.json): the deflection along the tool axis, the
// tool point's deflection and the struts' tensions over the program's points (x: the time at the programmed
// feeds, or the path length), and the 3-D animation with the deflected path beside the nominal one, coloured
// by the error along the tool axis.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "report/csv_table.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

double stiffness_summary_number(const nlohmann::json& summary, const char* key) {
  return summary.contains(key) && summary[key].is_number() ? summary[key].get<double>()
                                                           : std::numeric_limits<double>::quiet_NaN();
}

int stiffness_summary_line(const nlohmann::json& summary, const char* key) {
  return summary.contains(key) && summary[key].is_number_integer() ? summary[key].get<int>() : 0;
}

// The summary table of a stiffness run, from its summary.json.
nlohmann::json stiffness_table(const nlohmann::json& sm, double duration_s, const RunFiles& files,
                               const Machine& machine) {
  nlohmann::json table = nlohmann::json::array();
  table.push_back(table_row("Stiffness model", sm.value("model", std::string("?"))));
  table.push_back(table_row("Points (cutting)",
                            fmt::format("{} ({})", sm.value("points", 0L), sm.value("cutting_points", 0L))));
  table.push_back(table_row("Time at the programmed feeds / path length",
                            fmt::format("{} / {}", with_unit(duration_s, "s"),
                                        with_unit(stiffness_summary_number(sm, "path_length_mm"), "mm"))));
  table.push_back(table_row("Max deflection along the tool axis",
                            with_unit(stiffness_summary_number(sm, "max_normal_deflection_mm"), "mm"),
                            stiffness_summary_line(sm, "max_normal_deflection_line")));
  table.push_back(table_row("Rms deflection along the tool axis (cutting)",
                            with_unit(stiffness_summary_number(sm, "rms_normal_deflection_mm"), "mm")));
  table.push_back(table_row("Max tool deflection",
                            with_unit(stiffness_summary_number(sm, "max_deflection_mm"), "mm"),
                            stiffness_summary_line(sm, "max_deflection_line")));
  table.push_back(table_row(fmt::format("Max strut tension (strut {})", sm.value("max_strut_force_strut", 0)),
                            with_unit(stiffness_summary_number(sm, "max_strut_force_N"), "N"),
                            stiffness_summary_line(sm, "max_strut_force_line")));
  if (sm.contains("compensation") && sm["compensation"].is_object()) {
    const nlohmann::json& k = sm["compensation"];
    table.push_back(table_row("Pre-compensated program", k.value("program", std::string())));
    table.push_back(
        table_row("Largest correction / residual",
                  fmt::format("{} / {}", with_unit(stiffness_summary_number(k, "max_correction_mm"), "mm"),
                              with_unit(stiffness_summary_number(k, "max_residual_mm"), "mm")),
                  stiffness_summary_line(k, "max_correction_line")));
  }
  table.push_back(table_row("Program", files.program));
  table.push_back(table_row("Machine file", machine.source));
  return table;
}

}  // namespace

Result<nlohmann::json> stiffness_report(const Machine& machine, const RunFiles& files,
                                        const ReportOptions& options) {
  const std::string points_file = (fs::path(files.directory) / "points.csv").string();
  const nlohmann::json& sm = files.summary;
  auto rows = expected_rows(sm, "points", points_file);
  if (!rows) return rows.error();
  CsvReader points;
  if (Status opened = points.open(points_file); !opened) return opened.error();
  std::vector<int> column;
  for (const char* name :
       {"time_s", "s_mm", "line", "x_mm", "y_mm", "z_mm", "a_abc_deg", "b_abc_deg", "c_abc_deg", "dx_mm",
        "dy_mm", "dz_mm", "normal_mm", "deflected_x_mm", "deflected_y_mm", "deflected_z_mm"}) {
    auto found = points.require(name);
    if (!found) return found.error();
    column.push_back(*found);
  }
  const int n = machine.mechanism->actuator_count();
  std::vector<int> force_columns;
  for (int j = 1; j <= n; ++j) {
    auto found = points.require(fmt::format("F{}_N", j));
    if (!found) return found.error();
    force_columns.push_back(*found);
  }
  const double duration_s = stiffness_summary_number(sm, "duration_at_feed_s");
  MinMaxDecimator normal(1, *rows, options.chart_buckets);
  MinMaxDecimator deflection(4, *rows, options.chart_buckets);
  MinMaxDecimator forces(n, *rows, options.chart_buckets);
  SceneBuilder scene(machine, std::isfinite(duration_s) ? duration_s : 0.0, *rows, options.frames,
                     options.path_points);
  const std::vector<double> closeness(static_cast<std::size_t>(n), 0.0);
  std::vector<double> row, force(static_cast<std::size_t>(n));
  long count = 0;
  const auto at = [&](int k) { return row[static_cast<std::size_t>(column[static_cast<std::size_t>(k)])]; };
  while (points.next(row)) {
    const double t = at(0), s = at(1);
    const int line = static_cast<int>(at(2));
    const Eigen::Vector3d nominal(at(3), at(4), at(5));
    const Eigen::Vector3d moved(at(9), at(10), at(11));
    const double normal_um = 1e3 * at(12);
    normal.add(t, s, &normal_um);
    const double deflection_um[4] = {1e3 * moved.norm(), 1e3 * moved.x(), 1e3 * moved.y(), 1e3 * moved.z()};
    deflection.add(t, s, deflection_um);
    for (int j = 0; j < n; ++j)
      force[static_cast<std::size_t>(j)] =
          row[static_cast<std::size_t>(force_columns[static_cast<std::size_t>(j)])];
    forces.add(t, s, force.data());
    scene.add_path_point(nominal, Eigen::Vector3d(at(13), at(14), at(15)), std::abs(at(12)));
    if (scene.frame_due(t)) {
      const Pose pose{nominal,
                      rotation_from_angles(AngleConvention::abc,
                                           Eigen::Vector3d(at(6), at(7), at(8)) * rad_from_deg(1.0))};
      scene.add_frame(t, line, pose, closeness);
      scene.add_frame_forces(force);
    }
    ++count;
  }
  if (points.error()) return *points.error();
  if (count == 0) return make_error(ErrorCode::bad_input, fmt::format("{}: no rows", points_file));
  for (auto* d : {&normal, &deflection, &forces}) d->finish();
  double peak_force = 0.0;
  for (int j = 0; j < n; ++j) peak_force = std::max(peak_force, forces.peak(j));
  scene.set_force_scale(peak_force, "N");

  nlohmann::json charts = nlohmann::json::array();
  charts.push_back(chart_json("normal_deflection", "Deflection along the tool axis (surface error)",
                              "deflection", "µm", normal, {"along the tool axis"}, true));
  charts.push_back(chart_json("tool_deflection", "Tool point deflection", "deflection", "µm", deflection,
                              {"|δ|", "δx", "δy", "δz"}, true));
  std::vector<std::string> force_names;
  for (int j = 1; j <= n; ++j) force_names.push_back(fmt::format("F{}", j));
  charts.push_back(chart_json("strut_forces", "Strut tensions", "tension", "N", forces, force_names, true));

  nlohmann::json table = stiffness_table(sm, duration_s, files, machine);

  ReportParts parts;
  parts.kind = "stiffness";
  parts.title = fmt::format("{} on {}: deflection under load", fs::path(files.program).filename().string(),
                            machine.name);
  parts.program_file = files.program;
  parts.table = std::move(table);
  parts.summary = files.summary;
  parts.charts = std::move(charts);
  return report_document(machine, std::move(parts), scene);
}

}  // namespace pkm::report
