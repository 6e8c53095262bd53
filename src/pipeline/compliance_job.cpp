#include "pipeline/compliance_job.hpp"

#include <fmt/format.h>

#include "formats/stiffness_csv.hpp"

namespace pkm::pipeline {
namespace {

Error compliance_named(const std::string& name, Error error) {
  if (!name.empty()) error.message = name + ": " + error.message;
  return error;
}

// The tool's compliance at the pose; errors of the machine file keep their own place.
Result<stiffness::ToolCompliance> compliance_at_pose(const Machine& machine, const ComplianceJob& job) {
  const Mechanism& mech = *machine.mechanism;
  auto actuators = mech.inverse(job.pose);
  Status in_range = actuators ? check_actuator_range(machine, *actuators) : Status(actuators.error());
  auto parameters = stiffness::strut_stiffness_of(machine);
  auto compliance = !in_range     ? Result<stiffness::ToolCompliance>(in_range.error())
                    : !parameters ? Result<stiffness::ToolCompliance>(parameters.error())
                                  : stiffness::strut_compliance(mech, *parameters, job.pose);
  if (compliance || !compliance.error().location.file.empty()) return compliance;
  return compliance_named(job.pose_name, compliance.error());
}

// The Bode data: a bad request is the caller's, a machine file's error its own, anything else the pose's.
Result<stiffness::BodeData> bode_at_pose(const Machine& machine, const ComplianceJob& job) {
  const stiffness::BodeRequest& request = *job.bode;
  if (!(request.f_max_Hz > request.f_min_Hz)) {
    return make_error(ErrorCode::bad_input, fmt::format("f_max_Hz {:g} must be above f_min_Hz {:g}",
                                                        request.f_max_Hz, request.f_min_Hz));
  }
  auto data = stiffness::machine_bode(machine, job.pose, request);
  if (data || !data.error().location.file.empty() || data.error().code == ErrorCode::bad_input) return data;
  return compliance_named(job.pose_name, data.error());
}

}  // namespace

Result<ComplianceJobResult> run_compliance_job(const Machine& machine, const ComplianceJob& job) {
  auto compliance = compliance_at_pose(machine, job);
  if (!compliance) return compliance.error();
  ComplianceJobResult out{std::move(*compliance), std::nullopt};
  if (!job.bode) return out;
  auto data = bode_at_pose(machine, job);
  if (!data) return data.error();
  if (!job.bode_path.empty()) {
    if (Status written = formats::write_bode_csv(job.bode_path, *data); !written)
      return compliance_named(job.bode_name, written.error());
  }
  out.bode = std::move(*data);
  return out;
}

}  // namespace pkm::pipeline
