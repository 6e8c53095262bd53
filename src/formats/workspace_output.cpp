#include "formats/workspace_output.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"
#include "dynamics/pose_grid_columns.hpp"
#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "io/pose_input.hpp"
#include "io/version.hpp"

namespace pkm::formats {

using namespace workspace;  // the maps and margins these files lay out
namespace {

// The layers a map has, in the CSV's order.
std::vector<Layer> workspace_present_layers(const WorkspaceMap& map) {
  std::vector<Layer> present;
  for (const LayerInfo& info : workspace_layers()) {
    const bool has = !info.optional || (info.layer == Layer::lowest_stiffness && map.has_stiffness) ||
                     (info.layer == Layer::lowest_frequency && map.has_frequencies) ||
                     (info.layer == Layer::calibrated_error && map.has_calibrated_error);
    if (has) present.push_back(info.layer);
  }
  return present;
}

// Nine significant digits: the CSV is read back by the report and by tests comparing with the library.
void append_workspace_value(std::string& row, double value) {
  row += ',';
  if (std::isfinite(value)) fmt::format_to(std::back_inserter(row), "{:.9g}", value);
}

nlohmann::json workspace_json_value(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json workspace_cell_pose_json(const Mechanism& mechanism, const GridCells& cells, long cell) {
  if (cell < 0) return nullptr;
  return user_from_pose(mechanism, cells.pose(cell));
}

}  // namespace

std::string limit_text(const WorkspaceCell& cell) {
  const int number = cell.limit_index + 1;
  switch (cell.limit) {
    case CellLimit::none:
      return "";
    case CellLimit::actuator_min:
      return fmt::format("q{}_min", number);
    case CellLimit::actuator_max:
      return fmt::format("q{}_max", number);
    case CellLimit::base_joint:
      return fmt::format("base_joint_{}", number);
    case CellLimit::platform_joint:
      return fmt::format("platform_joint_{}", number);
    case CellLimit::condition_number:
      return "condition_number";
  }
  return "";
}

std::string axis_column(const Mechanism& mechanism, int coordinate) {
  const auto names = pose_coordinate_names(mechanism);
  return fmt::format("{}_{}", names[static_cast<std::size_t>(coordinate)], coordinate < 3 ? "mm" : "deg");
}

std::string workspace_csv(const Mechanism& mechanism, const WorkspaceMap& map) {
  const std::vector<Layer> layers = workspace_present_layers(map);
  std::string csv =
      fmt::format("{},status,limit,det_sign", fmt::join(dynamics::grid_pose_columns(mechanism), ","));
  for (Layer layer : layers) fmt::format_to(std::back_inserter(csv), ",{}", layer_info(layer).column);
  csv += '\n';
  const GridCells cells(map.grid, mechanism.convention());
  for (long i = 0; i < static_cast<long>(map.cells.size()); ++i) {
    const WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    csv += dynamics::grid_pose_cells(mechanism, cells.pose(i));
    fmt::format_to(std::back_inserter(csv), "{},{},{}", to_string(cell.status), limit_text(cell),
                   static_cast<int>(cell.determinant_sign));
    for (Layer layer : layers) append_workspace_value(csv, layer_value(cell, layer));
    csv += '\n';
  }
  return csv;
}

nlohmann::json workspace_summary_json(const Machine& machine, const WorkspaceMap& map,
                                      const WorkspaceMapSummary& summary) {
  const Mechanism& mechanism = *machine.mechanism;
  const auto names = pose_coordinate_names(mechanism);
  nlohmann::json axes = nlohmann::json::array();
  for (std::size_t a = 0; a < map.grid.axes.size(); ++a) {
    const GridAxis& axis = map.grid.axes[a];
    const bool angle = axis.coordinate >= 3;
    const double scale = angle ? deg_from_rad(1.0) : 1.0;
    axes.push_back({{"coordinate", names[static_cast<std::size_t>(axis.coordinate)]},
                    {"column", axis_column(mechanism, axis.coordinate)},
                    {"unit", angle ? "deg" : "mm"},
                    {"half_range", axis.half_range_mm_or_rad * scale},
                    {"step", axis.step_mm_or_rad * scale},
                    {"points", map.points_per_axis[a]}});
  }
  nlohmann::json status = nlohmann::json::object();
  for (int k = 0; k < kCellStatusCount; ++k) {
    status[to_string(static_cast<CellStatus>(k))] = summary.status_cells[static_cast<std::size_t>(k)];
  }
  nlohmann::json by_actuator = nlohmann::json::object();
  for (int j = 0; j < mechanism.actuator_count(); ++j) {
    by_actuator[fmt::format("q{}", j + 1)] = summary.actuator_range_cells[static_cast<std::size_t>(j)];
  }
  const GridCells cells(map.grid, mechanism.convention());
  nlohmann::json layers = nlohmann::json::object();
  for (Layer layer : workspace_present_layers(map)) {
    const LayerExtremes& e = summary.layers[static_cast<std::size_t>(layer)];
    layers[std::string(layer_info(layer).column)] = {
        {"label", layer_info(layer).label},
        {"unit", layer_info(layer).unit},
        {"cells", e.cells},
        {"min", workspace_json_value(e.min)},
        {"min_pose", workspace_cell_pose_json(mechanism, cells, e.min_cell)},
        {"max", workspace_json_value(e.max)},
        {"max_pose", workspace_cell_pose_json(mechanism, cells, e.max_cell)}};
  }
  const long ok = summary.status_cells[static_cast<std::size_t>(CellStatus::ok)];
  return {{"kind", "workspace"},
          {"pkm_version", std::string(pkm_version())},
          {"machine", machine.source},
          {"machine_name", machine.name},
          {"grid",
           {{"kind", map.grid.axes.size() == 3 ? "grid3d" : "section"},
            {"centre", user_from_pose(mechanism, map.grid.centre)},
            {"axes", axes}}},
          {"cells", summary.cells},
          {"reachable_share", summary.cells > 0 ? static_cast<double>(ok) / summary.cells : 0.0},
          {"status", status},
          {"actuator_range_by_actuator", by_actuator},
          {"determinant_sign",
           {{"positive", summary.determinant_positive}, {"negative", summary.determinant_negative}}},
          {"layers", layers}};
}

Status stage_workspace_files(OutputSet& outputs, const Machine& machine, const WorkspaceMap& map,
                             const WorkspaceMapSummary& summary) {
  if (Status written =
          write_file_atomically(outputs.staged_path(kWorkspaceCsv), workspace_csv(*machine.mechanism, map));
      !written) {
    return written;
  }
  return write_file_atomically(outputs.staged_path(kWorkspaceSummaryJson),
                               json_text(workspace_summary_json(machine, map, summary)) + "\n");
}

}  // namespace pkm::formats
