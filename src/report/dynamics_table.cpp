#include "report/dynamics_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "report/report_data.hpp"
#include "report/run_reports.hpp"

namespace pkm::report {

namespace {

double number_at(const nlohmann::json& object, const std::string& key) {
  return object.contains(key) && object[key].is_number() ? object[key].get<double>()
                                                         : std::numeric_limits<double>::quiet_NaN();
}

int line_at(const nlohmann::json& object, const char* key) {
  return object.contains(key) && object[key].is_number_integer() ? object[key].get<int>() : 0;
}

/// The summary's key suffix and the unit shown: angular drives give torques (peak_force_Nmm).
struct ForceUnit {
  std::string key, shown;
};

ForceUnit force_unit_of(const nlohmann::json& drive) {
  return drive.contains("peak_force_Nmm") ? ForceUnit{"Nmm", "N·mm"} : ForceUnit{"N", "N"};
}

const nlohmann::json* dynamics_block(const nlohmann::json& summary) {
  return summary.contains("dynamics") && summary["dynamics"].is_object() ? &summary["dynamics"] : nullptr;
}

}  // namespace

nlohmann::json dynamics_table_rows(const nlohmann::json& summary) {
  nlohmann::json rows = nlohmann::json::array();
  const nlohmann::json* block = dynamics_block(summary);
  if (block == nullptr) return rows;
  const nlohmann::json& d = *block;
  const nlohmann::json drives = d.value("drives", nlohmann::json::array());
  double peak_power_W = 0.0, peak_static = 0.0, peak_dynamic = 0.0;
  int peak_power_drive = 0;
  ForceUnit unit{"N", "N"};
  for (std::size_t j = 0; j < drives.size(); ++j) {
    const nlohmann::json& drive = drives[j];
    unit = force_unit_of(drive);
    rows.push_back(
        table_row(fmt::format("Peak force, drive {}", j + 1),
                  fmt::format("{} at {}", with_unit(number_at(drive, "peak_force_" + unit.key), unit.shown),
                              with_unit(number_at(drive, "peak_force_time_s"), "s")),
                  line_at(drive, "peak_force_line")));
    peak_static = std::max(peak_static, number_at(drive, "peak_static_" + unit.key));
    peak_dynamic = std::max(peak_dynamic, number_at(drive, "peak_dynamic_" + unit.key));
    const double power_W = number_at(drive, "peak_power_W");
    if (power_W > peak_power_W) peak_power_W = power_W, peak_power_drive = static_cast<int>(j) + 1;
  }
  if (!drives.empty()) {
    // The parts' peaks may come at other moments than the total's: they bound its parts, over all drives.
    rows.push_back(table_row(
        "Peak static / dynamic part",
        fmt::format("{} / {}", with_unit(peak_static, unit.shown), with_unit(peak_dynamic, unit.shown))));
  }
  if (peak_power_drive > 0) {
    rows.push_back(table_row("Peak drive power",
                             fmt::format("{} (drive {})", with_unit(peak_power_W, "W"), peak_power_drive)));
  }
  rows.push_back(table_row("Peak total power", with_unit(number_at(d, "peak_total_power_W"), "W"),
                           line_at(d, "peak_total_power_line")));
  rows.push_back(table_row("Energy: no recovery / braking free / recovery",
                           fmt::format("{} / {} / {}", with_unit(number_at(d, "energy_no_recovery_J"), "J"),
                                       with_unit(number_at(d, "energy_braking_free_J"), "J"),
                                       with_unit(number_at(d, "energy_recovery_J"), "J"))));
  if (d.contains("lowest_natural_frequency_Hz")) {
    rows.push_back(table_row("Lowest natural frequency (at the start)",
                             with_unit(number_at(d, "lowest_natural_frequency_Hz"), "Hz")));
  }
  if (d.contains("max_dynamic_tool_error_mm")) {
    rows.push_back(
        table_row("Max dynamic tool error",
                  fmt::format("{} at {}", with_unit(number_at(d, "max_dynamic_tool_error_mm"), "mm"),
                              with_unit(number_at(d, "max_dynamic_tool_error_time_s"), "s")),
                  line_at(d, "max_dynamic_tool_error_line")));
    rows.push_back(
        table_row("Static sag / max dynamic rotation",
                  fmt::format("{} / {}", with_unit(number_at(d, "static_deflection_at_start_mm"), "mm"),
                              with_unit(number_at(d, "max_dynamic_rotation_deg"), "°"))));
  }
  return rows;
}

nlohmann::json dynamics_limit_entries(const nlohmann::json& summary,
                                      const std::optional<double>& force_limit_N) {
  nlohmann::json entries = nlohmann::json::array();
  const nlohmann::json* block = dynamics_block(summary);
  if (block == nullptr || !force_limit_N || !(*force_limit_N > 0.0)) return entries;
  const nlohmann::json drives = block->value("drives", nlohmann::json::array());
  for (std::size_t j = 0; j < drives.size(); ++j) {
    const ForceUnit unit = force_unit_of(drives[j]);
    const double peak = number_at(drives[j], "peak_force_" + unit.key);
    if (!(peak >= 0.99 * *force_limit_N)) continue;
    entries.push_back(
        {{"what", fmt::format("drive {} force {:.6g} {} ({:.1f} % of actuator_force_max {:.6g} {})", j + 1,
                              peak, unit.shown, 100.0 * peak / *force_limit_N, *force_limit_N, unit.shown)},
         {"line", line_at(drives[j], "peak_force_line")},
         {"time_s", number_at(drives[j], "peak_force_time_s")},
         {"severity", peak > *force_limit_N * (1.0 + 1e-3) ? "exceeded" : "reached"}});
  }
  return entries;
}

}  // namespace pkm::report
