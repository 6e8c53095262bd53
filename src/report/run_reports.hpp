#pragma once
// The report builders of each kind of run (report_data.hpp dispatches by the directory's files).
#include <nlohmann/json.hpp>
#include <string>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "report/report_data.hpp"

namespace pkm::report {

struct RunFiles {
  std::string directory;
  nlohmann::json summary;
  std::string program;  ///< the part program, for its source lines ("" or unreadable: none)
};

/// `pkm plan`: actuators.csv + path.csv.
Result<nlohmann::json> plan_report(const Machine& machine, const RunFiles& files,
                                   const ReportOptions& options);
/// `pkm interpolate`: steps.csv + contour.csv.
Result<nlohmann::json> interpolate_report(const Machine& machine, const RunFiles& files,
                                          const ReportOptions& options);

/// `pkm stiffness`: points.csv (the deflection at every point of a program).
Result<nlohmann::json> stiffness_report(const Machine& machine, const RunFiles& files,
                                        const ReportOptions& options);

/// "12.3 s", "4.56e-05 mm": a value with a unit for the summary table.
std::string with_unit(double value, const std::string& unit);

}  // namespace pkm::report
