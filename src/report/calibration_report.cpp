#include "report/calibration_report.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "io/csv_text.hpp"
#include "io/input_file.hpp"
#include "io/machine_file.hpp"
#include "io/pose_input.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"

namespace pkm::report {
namespace {

namespace fs = std::filesystem;
namespace csv = csv_text;

// A run's CSV with text fields (pose ids, parameter names): the rows as strings, by column name.
struct CalrepTable {
  std::string path;
  std::string text;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string_view>> rows;
  std::vector<int> lines;

  // The column's index; an error names the file when it is missing.
  Result<std::size_t> column(std::string_view name) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c;
    return make_error(ErrorCode::bad_input, fmt::format("{}: no column {}", path, name));
  }
};

// Fills `table` in place: its rows view its text, which must not move afterwards.
Status calrep_read(const std::string& path, CalrepTable& table) {
  table.path = path;
  auto text = read_text_input(path, "calibration output");
  if (!text) return text.error();
  table.text = std::move(*text);
  csv::Lines lines(table.text);
  std::string_view row;
  while (lines.next(row)) {
    if (csv::is_blank(row)) continue;
    std::vector<std::string_view> fields;
    for (const csv::Field& f : csv::split_row(row)) fields.push_back(f.text);
    if (table.columns.empty()) {
      table.columns.assign(fields.begin(), fields.end());
      continue;
    }
    if (fields.size() != table.columns.size()) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}:{}: expected {} fields, got {}", path, lines.number(),
                                    table.columns.size(), fields.size()));
    }
    table.rows.push_back(std::move(fields));
    table.lines.push_back(lines.number());
  }
  if (table.columns.empty()) return make_error(ErrorCode::bad_input, fmt::format("{}: empty", path));
  return ok_status();
}

// A number of a row (NaN when the field is not one: the page shows it as missing).
double calrep_number(std::string_view text) {
  double value = std::numeric_limits<double>::quiet_NaN();
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

double calrep_summary_number(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number()
             ? object[key].get<double>()
             : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json calrep_finite(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// Every residual before and after: {"labels", "lines", "before_mm", "after_mm"}.
Result<nlohmann::json> calrep_residuals(const CalrepTable& t) {
  auto id = t.column("pose_id"), quantity = t.column("quantity"), line = t.column("line"),
       before = t.column("before_mm"), after = t.column("after_mm");
  for (const auto* c : {&id, &quantity, &line, &before, &after})
    if (!*c) return c->error();
  nlohmann::json labels = nlohmann::json::array(), lines = nlohmann::json::array(),
                 before_mm = nlohmann::json::array(), after_mm = nlohmann::json::array();
  for (const auto& row : t.rows) {
    labels.push_back(fmt::format("{} {}", row[*id], row[*quantity]));
    lines.push_back(static_cast<int>(calrep_number(row[*line])));
    before_mm.push_back(calrep_finite(calrep_number(row[*before])));
    after_mm.push_back(calrep_finite(calrep_number(row[*after])));
  }
  return nlohmann::json{
      {"labels", labels}, {"lines", lines}, {"before_mm", before_mm}, {"after_mm", after_mm}};
}

// The parameter table: [{"name", "unit", "nominal", "identified", "change", "sigma", "identifiable"}].
Result<nlohmann::json> calrep_parameters(const CalrepTable& t) {
  nlohmann::json out = nlohmann::json::array();
  std::vector<std::size_t> c;
  for (const char* name : {"name", "unit", "nominal", "identified", "change", "sigma", "identifiable"}) {
    auto found = t.column(name);
    if (!found) return found.error();
    c.push_back(*found);
  }
  for (const auto& row : t.rows) {
    out.push_back({{"name", std::string(row[c[0]])},
                   {"unit", std::string(row[c[1]])},
                   {"nominal", calrep_finite(calrep_number(row[c[2]]))},
                   {"identified", calrep_finite(calrep_number(row[c[3]]))},
                   {"change", calrep_finite(calrep_number(row[c[4]]))},
                   {"sigma", calrep_finite(calrep_number(row[c[5]]))},
                   {"identifiable", row[c[6]] == "yes"}});
  }
  return out;
}

// The measured poses in the 3-D view, one second apart: the machine at each (identified model), and the tool
// points of the drawing and of the identified model as the two paths.
Status calrep_scene(const Machine& machine, const CalrepTable& t, SceneBuilder& scene) {
  const std::size_t values = user_from_pose(*machine.mechanism, machine.mechanism->home()).size();
  std::vector<std::size_t> pose_columns;
  const std::vector<std::string> names =
      values == 2   ? std::vector<std::string>{"x_mm", "y_mm"}
      : values == 3 ? std::vector<std::string>{"x_mm", "y_mm", "phi_deg"}
                    : std::vector<std::string>{"x_mm", "y_mm", "z_mm", "a1_deg", "a2_deg", "a3_deg"};
  for (const std::string& name : names) {
    auto found = t.column(name);
    if (!found) return found.error();
    pose_columns.push_back(*found);
  }
  auto line = t.column("line"), nx = t.column("nominal_x_mm"), ny = t.column("nominal_y_mm"),
       nz = t.column("nominal_z_mm"), correction = t.column("correction_mm");
  for (const auto* c : {&line, &nx, &ny, &nz, &correction})
    if (!*c) return c->error();
  const std::vector<double> closeness(static_cast<std::size_t>(machine.mechanism->actuator_count()), 0.0);
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    std::vector<double> user;
    for (std::size_t c : pose_columns) user.push_back(calrep_number(row[c]));
    auto pose = pose_from_user(*machine.mechanism, user, "poses.csv");
    if (!pose)
      return make_error(pose.error().code,
                        fmt::format("{}:{}: {}", t.path, t.lines[r], pose.error().message));
    const Eigen::Vector3d drawing(calrep_number(row[*nx]), calrep_number(row[*ny]), calrep_number(row[*nz]));
    scene.add_path_point(drawing, pose->position_mm, calrep_number(row[*correction]));
    const double time_s = static_cast<double>(r);
    if (scene.frame_due(time_s))
      scene.add_frame(time_s, static_cast<int>(calrep_number(row[*line])), *pose, closeness);
  }
  return ok_status();
}

nlohmann::json calrep_table(const nlohmann::json& sm, const Machine& machine) {
  const nlohmann::json& id = sm.value("identifiability", nlohmann::json::object());
  const nlohmann::json& before = sm.value("residuals_before", nlohmann::json::object());
  const nlohmann::json& after = sm.value("residuals_after", nlohmann::json::object());
  nlohmann::json table = nlohmann::json::array();
  table.push_back(table_row("Status", sm.value("status", std::string("?"))));
  table.push_back(table_row("Measurements",
                            fmt::format("{} ({}, {} poses, {} used)", sm.value("measurements", std::string()),
                                        sm.value("kind", std::string()), sm.value("poses", 0),
                                        sm.value("identification_poses", 0))));
  table.push_back(table_row("Parameters identified (rank)",
                            fmt::format("{} of {}", id.value("rank", 0), id.value("parameters", 0))));
  table.push_back(
      table_row("Condition number (identifiable directions)",
                fmt::format("{:.4g}", calrep_summary_number(id, "identifiable_condition_number"))));
  table.push_back(table_row("Residual rms before → after",
                            fmt::format("{} → {}", with_unit(calrep_summary_number(before, "rms_mm"), "mm"),
                                        with_unit(calrep_summary_number(after, "rms_mm"), "mm"))));
  table.push_back(table_row("Residual max before → after",
                            fmt::format("{} → {}", with_unit(calrep_summary_number(before, "max_mm"), "mm"),
                                        with_unit(calrep_summary_number(after, "max_mm"), "mm"))));
  table.push_back(table_row("Variance factor (1: the sigmas fit)",
                            fmt::format("{:.3g}", calrep_summary_number(sm, "variance_factor"))));
  if (sm.contains("held_out") && sm["held_out"].is_object()) {
    const nlohmann::json& h = sm["held_out"];
    table.push_back(
        table_row(fmt::format("Held-out error rms ({} poses) before → after", h.value("poses", 0)),
                  fmt::format("{} → {}", with_unit(calrep_summary_number(h, "rms_before_mm"), "mm"),
                              with_unit(calrep_summary_number(h, "rms_after_mm"), "mm"))));
  }
  if (id.contains("unidentifiable_combinations")) {
    for (const auto& c : id["unidentifiable_combinations"])
      table.push_back(table_row("Not identifiable", c.value("combination", std::string())));
  }
  // The summary's warnings are the report's `warnings` (report_document), shown in the verdict, not here.
  table.push_back(table_row("Calibrated machine file", sm.value("calibrated_machine", std::string())));
  table.push_back(table_row("Machine file (drawing)", machine.source));
  return table;
}

}  // namespace

Result<nlohmann::json> calibration_report(const std::string& directory, const nlohmann::json& summary,
                                          const ReportOptions& options) {
  const fs::path dir(directory);
  const std::string machine_file =
      options.machine_file.empty() ? summary.value("machine", std::string()) : options.machine_file;
  auto machine = load_machine_file(machine_file);
  if (!machine) {
    // As the other reports: the summary's machine may have moved; the caller can name another.
    Error error = make_error(machine.error().code,
                             fmt::format("{} (the machine of {}; name another machine file)",
                                         machine.error().message, (dir / "summary.json").string()));
    error.location = ErrorLocation{(dir / "summary.json").string(), 0, 0, "machine"};
    return error;
  }
  CalrepTable residuals, parameters, poses;
  for (auto [table, name] : {std::pair{&residuals, "residuals.csv"}, std::pair{&parameters, "parameters.csv"},
                             std::pair{&poses, "poses.csv"}}) {
    if (Status read = calrep_read((dir / name).string(), *table); !read) return read.error();
  }
  auto residual_json = calrep_residuals(residuals);
  if (!residual_json) return residual_json.error();
  auto parameter_json = calrep_parameters(parameters);
  if (!parameter_json) return parameter_json.error();

  const long count = static_cast<long>(poses.rows.size());
  SceneBuilder scene(*machine, static_cast<double>(std::max(1L, count)), std::max(1L, count), options.frames,
                     options.path_points);
  if (Status s = calrep_scene(*machine, poses, scene); !s) return s.error();

  ReportParts parts;
  parts.kind = "calibration";
  const std::string measurements = summary.value("measurements", std::string());
  parts.title =
      fmt::format("{} on {}: calibration", fs::path(measurements).filename().string(), machine->name);
  // The frames' lines are the measurement file's: the page shows its rows as a program's.
  parts.program_file = measurements;
  parts.table = calrep_table(summary, *machine);
  parts.summary = summary;
  nlohmann::json report = report_document(*machine, std::move(parts), scene);
  // The frames are the measured poses one second apart: a slide show, not a time axis.
  report["scene"]["frames"]["axis"] = "pose";
  report["calibration"] = {{"residuals", std::move(*residual_json)},
                           {"parameters", std::move(*parameter_json)},
                           {"status", summary.value("status", std::string())}};
  return report;
}

}  // namespace pkm::report
