#include "report/workspace_report.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "formats/workspace_output.hpp"
#include "io/csv_text.hpp"
#include "io/input_file.hpp"
#include "io/machine_file.hpp"
#include "io/pose_input.hpp"
#include "report/decimator.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"
#include "workspace/workspace_layers.hpp"

namespace pkm::report {
namespace {

namespace fs = std::filesystem;
using workspace::CellStatus;

constexpr double kWorkspaceReportNone = std::numeric_limits<double>::quiet_NaN();

// One grid axis as the summary gives it, and the cells of it the heat maps keep.
struct ReportAxis {
  std::string column;
  int points = 1;
  int stride = 1;
  std::vector<int> kept_at;   // per index: its place among the kept ones, −1 if dropped
  std::vector<double> value;  // per kept index: the CSV's value
};

Error workspace_report_error(const std::string& where, const std::string& what) {
  return make_error(ErrorCode::bad_input, fmt::format("{}: {}", where, what));
}

// Every k-th index with the centre among them, so the section through the centre is always drawn.
void keep_every_kth_cell(ReportAxis& axis, int most) {
  axis.stride = std::max(1, (axis.points + most - 1) / most);
  axis.kept_at.assign(static_cast<std::size_t>(axis.points), -1);
  int kept = 0;
  for (int i = (axis.points / 2) % axis.stride; i < axis.points; i += axis.stride) {
    axis.kept_at[static_cast<std::size_t>(i)] = kept++;
  }
  axis.value.assign(static_cast<std::size_t>(kept), kWorkspaceReportNone);
}

Result<std::vector<ReportAxis>> workspace_summary_axes(const nlohmann::json& summary,
                                                       const std::string& where) {
  if (!summary.contains("grid") || !summary["grid"].contains("axes") || !summary["grid"]["axes"].is_array())
    return workspace_report_error(where, "grid.axes: missing");
  std::vector<ReportAxis> axes;
  for (const auto& a : summary["grid"]["axes"]) {
    if (!a.contains("column") || !a["column"].is_string() || !a.contains("points") ||
        !a["points"].is_number_integer() || a["points"].get<int>() < 1) {
      return workspace_report_error(where, "grid.axes: each needs a column and a number of points");
    }
    axes.push_back({a["column"].get<std::string>(), a["points"].get<int>(), 1, {}, {}});
  }
  if (axes.size() != 2 && axes.size() != 3)
    return workspace_report_error(where, fmt::format("grid.axes: {} axes, not 2 or 3", axes.size()));
  const int most = axes.size() == 3 ? kWorkspaceGridCellsPerAxis : kWorkspaceSectionCellsPerAxis;
  for (ReportAxis& axis : axes) keep_every_kth_cell(axis, most);
  return axes;
}

std::vector<std::string_view> workspace_csv_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  csv_text::Fields cursor(line);
  for (std::string_view field; cursor.next(field);) fields.push_back(field);
  return fields;
}

// An empty field is no value; anything else must be a whole number.
bool workspace_csv_number(std::string_view field, double& value) {
  if (field.empty()) {
    value = kWorkspaceReportNone;
    return true;
  }
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  return error == std::errc() && end == field.data() + field.size();
}

int workspace_status_index(std::string_view word) {
  for (int k = 0; k < workspace::kCellStatusCount; ++k)
    if (word == workspace::to_string(static_cast<CellStatus>(k))) return k;
  return -1;
}

// A layer's kept cells as [slice][row][column].
nlohmann::json workspace_layer_values(const std::vector<double>& values, const std::vector<ReportAxis>& axes,
                                      bool categorical) {
  const std::size_t nx = axes[0].value.size(), ny = axes[1].value.size();
  const std::size_t nz = axes.size() == 3 ? axes[2].value.size() : 1;
  nlohmann::json slices = nlohmann::json::array();
  for (std::size_t k = 0; k < nz; ++k) {
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t j = 0; j < ny; ++j) {
      const auto first = values.begin() + static_cast<long>((k * ny + j) * nx);
      const std::vector<double> row(first, first + static_cast<long>(nx));
      if (categorical) {
        nlohmann::json r = nlohmann::json::array();
        for (double v : row)
          r.push_back(std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(static_cast<int>(v)));
        rows.push_back(std::move(r));
      } else {
        rows.push_back(json_numbers(row));
      }
    }
    slices.push_back(std::move(rows));
  }
  return slices;
}

// The numbers of a JSON array (a pose), whatever else it holds.
std::vector<double> workspace_numbers(const nlohmann::json& array) {
  std::vector<double> numbers;
  if (array.is_array())
    for (const auto& v : array)
      if (v.is_number()) numbers.push_back(v.get<double>());
  return numbers;
}

std::string workspace_summary_text(const nlohmann::json& summary, const char* key) {
  return summary.contains(key) && summary[key].is_string() ? summary[key].get<std::string>() : std::string();
}

// The table: the grid, the cells per status, which actuators stop the machine, each layer's range.
nlohmann::json workspace_table(const Machine& machine, const nlohmann::json& summary) {
  nlohmann::json table = nlohmann::json::array();
  std::string grid;
  for (const auto& a : summary["grid"]["axes"]) {
    if (!grid.empty()) grid += ", ";
    grid += fmt::format("{} ±{:g} {} by {:g} ({} points)", a.value("coordinate", std::string("?")),
                        a.value("half_range", 0.0), a.value("unit", std::string()), a.value("step", 0.0),
                        a.value("points", 0));
  }
  table.push_back(
      table_row(summary["grid"].value("kind", std::string()) == "grid3d" ? "3-D grid" : "Section", grid));
  const nlohmann::json centre = summary["grid"].value("centre", nlohmann::json::array());
  table.push_back(table_row("Centre", fmt::format("{:g}", fmt::join(workspace_numbers(centre), ", "))));
  const long cells = summary.value("cells", 0L);
  const nlohmann::json status = summary.value("status", nlohmann::json::object());
  table.push_back(
      table_row("Cells", fmt::format("{}, of them ok {} ({:.1f} %)", cells, status.value("ok", 0L),
                                     100.0 * summary.value("reachable_share", 0.0))));
  for (int k = 1; k < workspace::kCellStatusCount; ++k) {
    const char* word = workspace::to_string(static_cast<CellStatus>(k));
    table.push_back(table_row(fmt::format("Cells {}", word), std::to_string(status.value(word, 0L))));
  }
  std::string stopping;
  const nlohmann::json by_actuator = summary.value("actuator_range_by_actuator", nlohmann::json::object());
  for (const auto& [actuator, n] : by_actuator.items()) {
    if (n.is_number_integer() && n.get<long>() > 0)
      stopping += fmt::format("{}{} {}", stopping.empty() ? "" : ", ", actuator, n.get<long>());
  }
  if (!stopping.empty()) table.push_back(table_row("Stopped by actuator (cells)", stopping));
  const nlohmann::json sign = summary.value("determinant_sign", nlohmann::json::object());
  table.push_back(table_row(
      "det J over the ok cells",
      fmt::format("{} positive, {} negative", sign.value("positive", 0L), sign.value("negative", 0L))));
  const nlohmann::json layers = summary.value("layers", nlohmann::json::object());
  for (const workspace::LayerInfo& info : workspace::workspace_layers()) {
    const std::string key(info.column);
    if (!layers.contains(key) || !layers[key]["min"].is_number()) continue;
    const nlohmann::json& l = layers[key];
    table.push_back(table_row(fmt::format("{} (ok cells)", info.label),
                              fmt::format("{:.4g} … {:.4g}{}{}", l["min"].get<double>(),
                                          l["max"].get<double>(), info.unit.empty() ? "" : " ", info.unit)));
  }
  table.push_back(table_row("Machine file", machine.source));
  return table;
}

// The machine at the grid's centre, and the outline of a section of positions (or of the 3-D grid's box)
// as the path, so that the 3-D view shows where the map lies.
void workspace_scene(const Machine& machine, const nlohmann::json& summary, SceneBuilder& scene) {
  Pose centre = machine.mechanism->home();
  const nlohmann::json c = summary["grid"].value("centre", nlohmann::json::array());
  if (c.is_array()) {
    if (auto pose = pose_from_user(*machine.mechanism, workspace_numbers(c), "centre"); pose) centre = *pose;
  }
  scene.add_frame(0.0, 0, centre,
                  std::vector<double>(static_cast<std::size_t>(machine.mechanism->actuator_count()), 0.0));
  std::vector<int> coordinate;
  std::vector<double> half;
  for (const auto& a : summary["grid"]["axes"]) {
    const std::string name = a.value("column", std::string());
    if (name.size() < 3 || name.substr(name.size() - 3) != "_mm") return;  // an angle: no outline in space
    coordinate.push_back(name[0] == 'x' ? 0 : name[0] == 'y' ? 1 : 2);
    half.push_back(a.value("half_range", 0.0));
  }
  const auto corner = [&](double s, double t, double u) {
    Eigen::Vector3d p = centre.position_mm;
    const double sign[3] = {s, t, u};
    for (std::size_t k = 0; k < coordinate.size(); ++k) p[coordinate[k]] += sign[k] * half[k];
    scene.add_path_point(p, p, 0.0);
  };
  for (double u : coordinate.size() == 3 ? std::vector<double>{-1.0, 1.0} : std::vector<double>{0.0}) {
    for (const auto& [s, t] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}})
      corner(s, t, u);
  }
}

Result<Machine> workspace_report_machine(const std::string& directory, const nlohmann::json& summary,
                                         const ReportOptions& options) {
  const std::string summary_path = (fs::path(directory) / formats::kWorkspaceSummaryJson).string();
  std::string file = options.machine_file;
  if (file.empty()) file = workspace_summary_text(summary, "machine");
  if (file.empty()) {
    Error error = workspace_report_error(summary_path, "machine: missing; name the machine file");
    error.location = ErrorLocation{summary_path, 0, 0, "machine"};
    return error;
  }
  auto machine = load_machine_file(file);
  if (!machine) {
    Error error =
        make_error(machine.error().code, fmt::format("{} (the machine of {}; name another machine file)",
                                                     machine.error().message, summary_path));
    error.location = ErrorLocation{summary_path, 0, 0, "machine"};
    return error;
  }
  return machine;
}

Result<nlohmann::json> workspace_report_of(const std::string& directory, const nlohmann::json& summary,
                                           const ReportOptions& options) {
  auto machine = workspace_report_machine(directory, summary, options);
  if (!machine) return machine.error();
  auto map = workspace_map_json((fs::path(directory) / formats::kWorkspaceCsv).string(), summary);
  if (!map) return map.error();
  SceneBuilder scene(*machine, 0.0, 16, 1, 16);
  workspace_scene(*machine, summary, scene);
  ReportParts parts;
  parts.kind = "workspace";
  parts.title = fmt::format("{}: workspace map", machine->name);
  parts.table = workspace_table(*machine, summary);
  parts.summary = summary;
  nlohmann::json report = report_document(*machine, std::move(parts), scene);
  report["workspace_map"] = std::move(*map);
  return report;
}

// A layer of workspace.csv the report shows, and its column.
struct LayerColumn {
  const workspace::LayerInfo* info;
  int field;
};

// The map's layers: the cells' status first (what a reader needs first), then each quantity with the end of
// its scale that is bad.
nlohmann::json workspace_layers_json(const std::vector<double>& status,
                                     const std::vector<std::vector<double>>& values,
                                     const std::vector<LayerColumn>& layers,
                                     const std::vector<ReportAxis>& axes) {
  nlohmann::json list = nlohmann::json::array();
  list.push_back({{"id", "status"},
                  {"label", "status"},
                  {"unit", ""},
                  {"categorical", true},
                  {"values", workspace_layer_values(status, axes, true)}});
  for (std::size_t l = 0; l < layers.size(); ++l) {
    // The bad end of the scale, drawn hot: weak stiffness and low frequencies, high δρ, conditions and
    // errors.
    const workspace::Layer layer = layers[l].info->layer;
    const bool low_is_bad =
        layer == workspace::Layer::lowest_stiffness || layer == workspace::Layer::lowest_frequency;
    list.push_back({{"id", std::string(layers[l].info->column)},
                    {"label", std::string(layers[l].info->label)},
                    {"unit", std::string(layers[l].info->unit)},
                    {"categorical", false},
                    {"hot", low_is_bad ? "low" : "high"},
                    {"values", workspace_layer_values(values[l], axes, false)}});
  }
  return list;
}

}  // namespace

Result<nlohmann::json> workspace_map_json(const std::string& csv_path, const nlohmann::json& summary) {
  auto axes = workspace_summary_axes(summary, csv_path);
  if (!axes) return axes.error();
  if (Status readable = check_input_file(csv_path, "workspace map"); !readable) return readable.error();
  std::ifstream in(csv_path);
  std::string line;
  if (!in || !std::getline(in, line)) return workspace_report_error(csv_path, "empty, no header");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string_view> header = workspace_csv_fields(line);
  const auto index_of = [&](std::string_view name) {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    return -1;
  };
  std::vector<int> axis_field;
  for (const ReportAxis& axis : *axes) {
    axis_field.push_back(index_of(axis.column));
    if (axis_field.back() < 0)
      return workspace_report_error(csv_path, fmt::format("no column {}", axis.column));
  }
  const int status_field = index_of("status");
  if (status_field < 0) return workspace_report_error(csv_path, "no column status");
  std::vector<LayerColumn> layers;
  for (const workspace::LayerInfo& info : workspace::workspace_layers())
    if (int field = index_of(info.column); field >= 0) layers.push_back({&info, field});
  const std::size_t nx = (*axes)[0].value.size(), ny = (*axes)[1].value.size();
  const std::size_t nz = axes->size() == 3 ? (*axes)[2].value.size() : 1;
  std::vector<double> status(nx * ny * nz, kWorkspaceReportNone);
  std::vector<std::vector<double>> values(layers.size(), status);
  long expected = 1;
  for (const ReportAxis& axis : *axes) expected *= axis.points;
  long row = 0;
  for (long number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string where = fmt::format("{}:{}", csv_path, number);
    if (row >= expected)
      return workspace_report_error(where, fmt::format("more rows than the grid's {} cells", expected));
    const std::vector<std::string_view> fields = workspace_csv_fields(line);
    if (fields.size() != header.size())
      return workspace_report_error(
          where, fmt::format("{} fields, the header has {}", fields.size(), header.size()));
    // Rows are in the grid's order, its first axis fastest: the row number is the cell.
    long rest = row++;
    std::size_t kept = 0, scale = 1;
    bool shown = true;
    for (std::size_t a = 0; a < axes->size(); ++a) {
      ReportAxis& axis = (*axes)[a];
      const int i = static_cast<int>(rest % axis.points);
      rest /= axis.points;
      const int at = axis.kept_at[static_cast<std::size_t>(i)];
      if (at < 0) {
        shown = false;
        continue;
      }
      double v = 0.0;
      if (!workspace_csv_number(fields[static_cast<std::size_t>(axis_field[a])], v) || std::isnan(v))
        return workspace_report_error(where, fmt::format("{}: not a number", axis.column));
      axis.value[static_cast<std::size_t>(at)] = v;
      kept += static_cast<std::size_t>(at) * scale;
      scale *= axis.value.size();
    }
    if (!shown) continue;
    const int s = workspace_status_index(fields[static_cast<std::size_t>(status_field)]);
    if (s < 0)
      return workspace_report_error(
          where, fmt::format("status: unknown word '{}'", fields[static_cast<std::size_t>(status_field)]));
    status[kept] = s;
    for (std::size_t l = 0; l < layers.size(); ++l) {
      if (!workspace_csv_number(fields[static_cast<std::size_t>(layers[l].field)], values[l][kept]))
        return workspace_report_error(where, fmt::format("{}: not a number", layers[l].info->column));
    }
  }
  if (row != expected)
    return workspace_report_error(csv_path, fmt::format("{} rows for a grid of {} cells", row, expected));

  nlohmann::json status_names = nlohmann::json::array();
  for (int k = 0; k < workspace::kCellStatusCount; ++k)
    status_names.push_back(workspace::to_string(static_cast<CellStatus>(k)));
  nlohmann::json list = workspace_layers_json(status, values, layers, *axes);
  const bool grid3d = axes->size() == 3;
  return nlohmann::json{{"file", fs::path(csv_path).filename().string()},
                        {"x_label", (*axes)[0].column},
                        {"y_label", (*axes)[1].column},
                        {"x", json_numbers((*axes)[0].value, 9)},
                        {"y", json_numbers((*axes)[1].value, 9)},
                        {"slice_label", grid3d ? nlohmann::json((*axes)[2].column) : nlohmann::json(nullptr)},
                        {"slices", grid3d ? json_numbers((*axes)[2].value, 9) : nlohmann::json::array()},
                        {"status_names", status_names},
                        {"layers", list}};
}

Result<nlohmann::json> workspace_report(const std::string& directory, const nlohmann::json& summary,
                                        const ReportOptions& options) {
  // summary.json is pkm's own, but may have been edited: a value of the wrong type is an error naming it.
  try {
    return workspace_report_of(directory, summary, options);
  } catch (const nlohmann::json::exception& e) {
    return workspace_report_error((fs::path(directory) / formats::kWorkspaceSummaryJson).string(),
                                  fmt::format("unexpected content: {}", e.what()));
  }
}

}  // namespace pkm::report
