#include "pipeline/calibration_identify_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

#include "calibration/statistics.hpp"
#include "io/version.hpp"
#include "pipeline/calibration_setup.hpp"

namespace pkm::pipeline {
namespace {

// Forward kinematics of the judged models: tight, as the errors judged may be micrometres.
const FkOptions kCalidFk{1e-12, 60, 1e-13, true};

// The observations of one pose as the model predicts them from its readings: errors in mm, appended to `out`.
Status calid_pose_errors(const Mechanism& model, const calibration::MeasurementSet& data,
                         const calibration::MeasuredPose& pose, const Pose& guess, Pose& solved,
                         std::vector<double>& out) {
  auto fk = model.forward(pose.readings, guess, kCalidFk);
  if (!fk) {
    return make_error(fk.error().code, fmt::format("{}:{}: held-out pose {}: {}", data.source, pose.line,
                                                   pose.id, fk.error().message));
  }
  solved = fk->pose;
  const Pose& p = fk->pose;
  for (const calibration::TargetObservation& t : pose.targets) {
    const Eigen::Vector3d predicted =
        p.position_mm + p.rotation * data.fixture[static_cast<std::size_t>(t.target)].position_mm;
    out.push_back((predicted - t.position_mm).norm());
  }
  for (const calibration::DistanceObservation& d : pose.distances)
    out.push_back(std::abs((p.position_mm - data.ballbar_centre_mm).norm() - d.distance_mm));
  return ok_status();
}

std::string_view calid_form(calibration::ResidualForm form) {
  switch (form) {
    case calibration::ResidualForm::pose_inverse:
      return "pose_inverse";
    case calibration::ResidualForm::targets_forward:
      return "targets_forward";
    case calibration::ResidualForm::ballbar_forward:
      return "ballbar_forward";
  }
  return "?";
}

// What row k of a block measures, and the file line it comes from.
std::pair<std::string, int> calid_row_label(const calibration::MeasurementSet& data,
                                            const calibration::ResidualBlock& block, int k) {
  const calibration::MeasuredPose& pose = data.poses[static_cast<std::size_t>(block.pose)];
  if (block.form == calibration::ResidualForm::pose_inverse) return {fmt::format("L{}", k + 1), pose.line};
  if (block.form == calibration::ResidualForm::ballbar_forward)
    return {"distance", pose.distances[static_cast<std::size_t>(k)].line};
  const calibration::TargetObservation& t = pose.targets[static_cast<std::size_t>(k / 3)];
  static constexpr const char* kAxes[3] = {"x", "y", "z"};
  return {fmt::format("{}.{}", data.fixture[static_cast<std::size_t>(t.target)].name, kAxes[k % 3]), t.line};
}

nlohmann::json calid_residual_json(const calibration::ResidualSummary& s) {
  return {{"rms_mm", s.rms_mm},
          {"max_mm", s.max_mm},
          {"weighted_rms", s.weighted_rms},
          {"weighted_max", s.weighted_max}};
}

// Parameters named in a combination the measurements cannot identify.
std::set<std::string> calid_unidentified(const calibration::IdentificationResult& result) {
  std::set<std::string> names(result.unchanged_parameters.begin(), result.unchanged_parameters.end());
  for (const calibration::ParameterCombination& c : result.at_start.unidentifiable)
    for (const auto& [name, component] : c.components) names.insert(name);
  return names;
}

}  // namespace

Result<HeldOutErrors> calibration_held_out_errors(const Mechanism& nominal, const Mechanism& identified,
                                                  const calibration::MeasurementSet& held_out) {
  HeldOutErrors errors;
  errors.poses = static_cast<int>(held_out.poses.size());
  std::vector<double> before, after;
  for (const calibration::MeasuredPose& pose : held_out.poses) {
    Pose at_nominal, at_identified;
    if (Status s = calid_pose_errors(nominal, held_out, pose, nominal.home(), at_nominal, before); !s)
      return s.error();
    if (Status s = calid_pose_errors(identified, held_out, pose, at_nominal, at_identified, after); !s)
      return s.error();
  }
  errors.measurements = static_cast<int>(before.size());
  if (before.empty()) return errors;
  errors.rms_before_mm = calibration::root_mean_square(before);
  errors.max_before_mm = *std::max_element(before.begin(), before.end());
  errors.rms_after_mm = calibration::root_mean_square(after);
  errors.max_after_mm = *std::max_element(after.begin(), after.end());
  return errors;
}

Result<std::string> calibration_residual_rows(const calibration::ResidualModel& residuals,
                                              const Mechanism& nominal, const Mechanism& identified) {
  Eigen::VectorXd raw_before, raw_after, weighted_before, weighted_after;
  std::vector<Pose> poses = residuals.start_poses();
  if (Status s = residuals.evaluate(nominal, poses, raw_before, &weighted_before); !s) return s.error();
  if (Status s = residuals.evaluate(identified, poses, raw_after, &weighted_after); !s) return s.error();
  const calibration::MeasurementSet& data = residuals.data();
  std::string csv = "pose_id,line,form,quantity,before_mm,after_mm,before_weighted,after_weighted\n";
  auto out = std::back_inserter(csv);
  for (const calibration::ResidualBlock& block : residuals.blocks()) {
    for (int k = 0; k < block.rows; ++k) {
      const int row = block.first_row + k;
      const auto [quantity, line] = calid_row_label(data, block, k);
      fmt::format_to(out, "{},{},{},{},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                     data.poses[static_cast<std::size_t>(block.pose)].id, line, calid_form(block.form),
                     quantity, raw_before[row], raw_after[row], weighted_before[row], weighted_after[row]);
    }
  }
  return csv;
}

Result<std::string> calibration_poses_csv(const Mechanism& nominal, const Mechanism& identified,
                                          const calibration::MeasurementSet& all,
                                          const std::vector<bool>& held_out) {
  std::string csv = fmt::format(
      "pose_id,line,held_out,{},nominal_x_mm,nominal_y_mm,nominal_z_mm,correction_mm{}\n",
      calibration_pose_header(identified), calibration_reading_header(identified.actuator_count()));
  auto out = std::back_inserter(csv);
  for (std::size_t p = 0; p < all.poses.size(); ++p) {
    const calibration::MeasuredPose& pose = all.poses[p];
    auto at_nominal = nominal.forward(pose.readings, nominal.home(), kCalidFk);
    if (!at_nominal) return at_nominal.error();
    auto at_identified = identified.forward(pose.readings, at_nominal->pose, kCalidFk);
    if (!at_identified) return at_identified.error();
    const Eigen::Vector3d& x = at_nominal->pose.position_mm;
    fmt::format_to(out, "{},{},{},{},{:.9f},{:.9f},{:.9f},{:.9g}{}\n", pose.id, pose.line,
                   held_out[p] ? 1 : 0, calibration_pose_fields(identified, at_identified->pose), x.x(),
                   x.y(), x.z(), (at_identified->pose.position_mm - x).norm(),
                   calibration_reading_fields(identified, pose.readings));
  }
  return csv;
}

std::string calibration_parameters_csv(const calibration::IdentificationResult& result) {
  const std::set<std::string> unidentified = calid_unidentified(result);
  std::string csv = "name,unit,nominal,identified,change,sigma,identifiable\n";
  auto out = std::back_inserter(csv);
  const calibration::ParameterLayout& layout = result.layout;
  const Eigen::VectorXd& sd = result.at_solution.standard_deviation;
  for (int i = 0; i < layout.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    fmt::format_to(out, "{},{},{:.15g},{:.15g},{:.9g},{:.6g},{}\n", layout.names[k], layout.units[k],
                   result.nominal[i], result.identified[i], result.identified[i] - result.nominal[i],
                   i < sd.size() ? sd[i] : 0.0, unidentified.count(layout.names[k]) ? "no" : "yes");
  }
  return csv;
}

nlohmann::json calibration_identify_summary(const Machine& machine, const CalibrationIdentifyJob& job,
                                            const calibration::MeasurementSet& all,
                                            const calibration::IdentificationResult& result,
                                            const HeldOutErrors& held_out, int identification_poses) {
  std::vector<std::string> warnings = result.warnings;
  if (result.status == calibration::IdentificationStatus::partially_identified) {
    warnings.insert(
        warnings.begin(),
        fmt::format("partially identified: the measurements determine {} of {} parameter directions; the "
                    "others stay at the drawing",
                    result.at_start.rank, result.at_start.parameters));
  }
  nlohmann::json summary = {
      {"command", "calibrate identify"},
      {"pkm_version", std::string(pkm_version())},
      {"machine", machine.source},
      {"measurements", job.measurements_path},
      {"kind", all.kind == calibration::MeasurementKind::ballbar ? "ballbar" : "tracker"},
      {"calibrated_machine", job.calibrated_path},
      {"poses", all.poses.size()},
      {"identification_poses", identification_poses},
      {"status", calibration::to_string(result.status)},
      {"solver",
       {{"message", result.solver_message},
        {"iterations", result.iterations},
        {"evaluations", result.evaluations},
        {"jacobians", result.jacobians}}},
      {"identifiability", calibration_identifiability_json(result.at_start)},
      {"residuals_before", calid_residual_json(result.before)},
      {"residuals_after", calid_residual_json(result.after)},
      {"variance_factor", result.variance_factor},
      {"unchanged_parameters", result.unchanged_parameters},
      {"warnings", warnings}};
  if (held_out.poses > 0) {
    summary["held_out"] = {{"poses", held_out.poses},
                           {"measurements", held_out.measurements},
                           {"rms_before_mm", held_out.rms_before_mm},
                           {"max_before_mm", held_out.max_before_mm},
                           {"rms_after_mm", held_out.rms_after_mm},
                           {"max_after_mm", held_out.max_after_mm}};
  }
  return summary;
}

}  // namespace pkm::pipeline
