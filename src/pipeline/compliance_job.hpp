#pragma once
// `pkm compliance --pose` (and Python's pkm.compliance) as one library call: the tool's compliance at a pose
// with the struts as the springs (stiffness/strut_compliance.hpp) and, if asked, the dynamic compliance's
// natural frequencies and Bode data (stiffness/compliance_bode.hpp), written as a CSV.
#include <optional>
#include <string>

#include "machine/machine.hpp"
#include "stiffness/compliance_bode.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::pipeline {

struct ComplianceJob {
  Pose pose;
  /// How messages about the pose name it (the CLI: "--pose 0,0,5000,0,0,0"); empty: not named.
  std::string pose_name;
  std::optional<stiffness::BodeRequest> bode;  ///< also the dynamic compliance (needs a dynamics: section)
  std::string bode_path;                       ///< the Bode data's CSV; empty: not written
  std::string bode_name = "bode_path";         ///< how messages about the CSV name it (the CLI: "--bode")
};

struct ComplianceJobResult {
  stiffness::ToolCompliance compliance;
  std::optional<stiffness::BodeData> bode;  ///< when asked for
};

/// Refuses a pose out of reach or beyond the actuator range (naming the pose), a machine without the struts'
/// stiffness, and with Bode data asked for, f_max_Hz not above f_min_Hz or a machine without the elastic
/// model. Everything is computed before the CSV is touched: a failure leaves no file behind.
Result<ComplianceJobResult> run_compliance_job(const Machine& machine, const ComplianceJob& job);

}  // namespace pkm::pipeline
