#include "formats/modes_margin_output.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"
#include "dynamics/pose_grid_columns.hpp"
#include "io/pose_input.hpp"

namespace pkm::formats {

using namespace workspace;  // the maps and margins these files lay out
namespace {

// Nine significant digits, empty where there is no value (as workspace.csv).
void append_margin_value(std::string& row, double value) {
  row += ',';
  if (std::isfinite(value)) fmt::format_to(std::back_inserter(row), "{:.9g}", value);
}

nlohmann::json margin_json_value(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json margin_extreme_json(const Mechanism& mechanism, const std::vector<ModesMarginSample>& samples,
                                   const std::optional<std::size_t>& index) {
  if (!index) return nullptr;
  const ModesMarginSample& s = samples[*index];
  return {
      {std::string("margin_") + margin_unit(mechanism), margin_in_user_unit(mechanism, s.margin.margin_mm)},
      {"status", margin_status(s.margin)},
      {"line", s.line},
      {"time_s", s.time_s},
      {"pose", user_from_pose(mechanism, s.margin.pose)},
      {"actuators", user_from_actuators(mechanism, s.margin.actuators)},
      {"singular_pose", user_from_pose(mechanism, s.margin.singular_pose)},
      {"singular_actuators", user_from_actuators(mechanism, s.margin.singular_actuators)},
      {"det_ratio", margin_json_value(s.margin.det_ratio)}};
}

}  // namespace

const char* margin_unit(const Mechanism& mechanism) {
  return actuator_unit_name(mechanism);
}

double margin_in_user_unit(const Mechanism& mechanism, double margin) {
  return mechanism.actuators_are_angles() ? deg_from_rad(margin) : margin;
}

const char* margin_status(const AssemblyModeMargin& margin) {
  if (!margin.found) return "none";
  return margin.note.empty() ? "found" : "bound";
}

std::string modes_margin_csv(const Mechanism& mechanism, const ProgramModesMargin& result) {
  const std::vector<std::string> pose_columns = dynamics::grid_pose_columns(mechanism);
  std::string csv = fmt::format("time_s,line,{},margin_status,margin_{},det_ratio",
                                fmt::join(pose_columns, ","), margin_unit(mechanism));
  for (const std::string& column : pose_columns)
    fmt::format_to(std::back_inserter(csv), ",singular_{}", column);
  csv += ",real_modes,other_mode_mm,other_mode_deg\n";
  for (const ModesMarginSample& s : result.samples) {
    fmt::format_to(std::back_inserter(csv), "{:.6f},{},", s.time_s, s.line);
    csv += dynamics::grid_pose_cells(mechanism, s.margin.pose);
    csv += margin_status(s.margin);
    append_margin_value(csv, s.margin.found ? margin_in_user_unit(mechanism, s.margin.margin_mm) : NAN);
    append_margin_value(csv, s.margin.found ? s.margin.det_ratio : NAN);
    if (s.margin.found) {
      for (double v : user_from_pose(mechanism, s.margin.singular_pose))
        fmt::format_to(std::back_inserter(csv), ",{:.6f}", v);
    } else {
      csv += std::string(pose_columns.size(), ',');
    }
    csv += ',';
    if (s.modes.enumerated) fmt::format_to(std::back_inserter(csv), "{}", s.modes.real_modes);
    append_margin_value(csv, s.modes.nearest_other_position_mm);
    append_margin_value(csv, s.modes.nearest_other_rotation_deg);
    csv += '\n';
  }
  return csv;
}

nlohmann::json modes_margin_summary_json(const Machine& machine, const ProgramModesMargin& result) {
  const Mechanism& mechanism = *machine.mechanism;
  const ModesMarginSummary& s = result.summary;
  nlohmann::json j = {
      {"kind", "modes_margin"},
      {"machine", machine.source},
      {"program", result.program_source},
      {"duration_s", result.duration_s},
      {"samples", s.samples},
      {"margin_unit", margin_unit(mechanism)},
      {"margins_found", s.margins_found},
      {"margins_bounded", s.margins_bounded},
      {"min_margin", margin_extreme_json(mechanism, result.samples, s.min_margin)},
      {"max_margin", margin_extreme_json(mechanism, result.samples, s.max_margin)},
      {"modes_enumerated", s.modes_enumerated},
      {"min_real_modes", s.modes_enumerated > 0 ? nlohmann::json(s.min_real_modes) : nullptr},
      {"max_real_modes", s.modes_enumerated > 0 ? nlohmann::json(s.max_real_modes) : nullptr},
      {"modes_note", s.modes_note.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.modes_note)}};
  if (s.nearest_other_mode) {
    const ModesMarginSample& n = result.samples[*s.nearest_other_mode];
    j["nearest_other_mode"] = {{"position_mm", n.modes.nearest_other_position_mm},
                               {"rotation_deg", n.modes.nearest_other_rotation_deg},
                               {"line", n.line},
                               {"time_s", n.time_s},
                               {"pose", user_from_pose(mechanism, n.margin.pose)},
                               {"other_pose", user_from_pose(mechanism, n.modes.nearest_other)}};
  } else {
    j["nearest_other_mode"] = nullptr;
  }
  return j;
}

}  // namespace pkm::formats
