#pragma once
// The stiffness plots of a run's report (Bode plots of the tool compliance, maps
// of stiffness over the workspace): when the run's directory holds `bode.csv`
// (stiffness/compliance_bode.hpp) or `stiffness_map.csv` (stiffness/stiffness_map.hpp), the report data gets
// a `frequency_response` or a `stiffness_map` object (docs/report-data.md) that the page draws as a Bode plot
// and a colour map. Read back from the files, as every other part of the report is.
#include <nlohmann/json.hpp>
#include <string>

#include "core/result.hpp"

namespace pkm::report {

/// The name of each file in a run's directory.
inline constexpr const char* kBodeCsv = "bode.csv";
inline constexpr const char* kStiffnessMapCsv = "stiffness_map.csv";

/// `frequency_response` from a Bode CSV: {"file", "frequency_Hz": [...], "entries": [{"name",
/// "magnitude_um_N": [...], "phase_deg": [...]}]}. Errors name the file (and line) where it is malformed.
Result<nlohmann::json> frequency_response_json(const std::string& path);

/// `stiffness_map` from a stiffness-map CSV: the grid's two moving pose columns as axes, the lowest stiffness
/// per cell (null where there is none), at most `max_per_axis` cells along each axis (every k-th otherwise).
Result<nlohmann::json> stiffness_map_json(const std::string& path, int max_per_axis = 401);

/// Adds `frequency_response` and `stiffness_map` to `report` for those files of `directory` that exist.
Status add_stiffness_plots(const std::string& directory, nlohmann::json& report);

}  // namespace pkm::report
