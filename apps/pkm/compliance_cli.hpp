#pragma once
// pkm compliance's parts beyond the static compliance at a pose (cmd_compliance.cpp): the dynamic
// compliance's Bode data (--bode, compliance_bode_cli.cpp) and the stiffness map (--map,
// compliance_map_cli.cpp). The library does the work (pipeline/compliance_job.hpp,
// pipeline/compliance_map_job.hpp); these read flags and print.
#include <nlohmann/json.hpp>
#include <string>

#include "map_grid.hpp"
#include "stiffness/compliance_bode.hpp"

namespace pkm::cli {

struct ComplianceBodeArguments {
  std::string path;  ///< empty: no Bode data asked for
  double f_min_Hz = 10.0;
  double f_max_Hz = 2000.0;
  int points = 200;
  double damping_ratio = 0.02;
  std::string rayleigh_text;  ///< "α,β" (1/s, s): Rayleigh damping instead of the modal ratio
};

/// The Bode request of the flags, or the error naming the flag: --f-max-hz not above --f-min-hz, a
/// --rayleigh that is not α,β or no damping.
Result<stiffness::BodeRequest> compliance_bode_request(const ComplianceBodeArguments& arguments);
/// The JSON block of a Bode run: the file, the range, the damping assumed, the natural frequencies, each
/// entry's peak.
nlohmann::json compliance_bode_json(const stiffness::BodeData& data,
                                    const ComplianceBodeArguments& arguments);
/// The same as text on stdout.
void print_compliance_bode(const stiffness::BodeData& data, const ComplianceBodeArguments& arguments);

struct ComplianceMapArguments {
  std::string machine_path;
  MapGridArguments grid;
  std::string out_path;
  bool json = false;
};

/// pkm compliance --map: the lowest translational stiffness over a plane grid, to a CSV, with a summary on
/// stdout; returns the exit code (errors reported as `pkm compliance: error: ...`).
int run_compliance_map(const ComplianceMapArguments& arguments);

}  // namespace pkm::cli
