// `pkm calibrate plan` (calibration_run.hpp): the poses to measure and what measuring them with the
// instrument would identify, written as plan.csv and summary.json.
#include "pipeline/calibration_run.hpp"

#include <fmt/format.h>

#include <iterator>

#include "calibration/plan_prediction.hpp"
#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/calibration_checks.hpp"
#include "pipeline/calibration_setup.hpp"

namespace pkm::pipeline {

Result<CalibrationPlanResult> calibration_plan(const Machine& machine, const CalibrationPlanJob& job) {
  if (Status valid = check_calibration_plan_spec(job.plan); !valid) return valid.error();
  if (Status valid = check_calibration_instrument(job.instrument); !valid) return valid.error();
  auto prepared = calibration_prepare(machine, job.plan, job.instrument);
  if (!prepared) return prepared.error();
  const calibration::Identifiability& id = prepared->prediction.identifiability;
  if (job.strict && !id.full_rank()) {
    return make_error(
        ErrorCode::singular,
        fmt::format("the {} plan of {} poses identifies {} of {} parameter directions (strict)",
                    to_string(job.plan.method), prepared->plan.poses.size(), id.rank, id.parameters));
  }

  OutputSet outputs{"calibrate plan"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  const Mechanism& mechanism = *prepared->model;
  const int n = mechanism.actuator_count();
  std::string csv =
      fmt::format("pose_id,{}{}\n", calibration_pose_header(mechanism), calibration_reading_header(n));
  const int count = static_cast<int>(prepared->plan.poses.size());
  for (int p = 0; p < count; ++p) {
    const Pose& pose = prepared->plan.poses[static_cast<std::size_t>(p)];
    auto readings = mechanism.inverse(pose);
    if (!readings) return readings.error();
    fmt::format_to(std::back_inserter(csv), "{},{}{}\n", calibration_pose_id(p, count),
                   calibration_pose_fields(mechanism, pose),
                   calibration_reading_fields(mechanism, *readings));
  }
  if (Status written = write_file_atomically(outputs.staged_path("plan.csv"), csv); !written)
    return written.error();

  std::vector<std::string> warnings = id.warnings;
  if (!id.full_rank()) {
    warnings.insert(
        warnings.begin(),
        fmt::format("not identifiable: the plan determines {} of {} parameter directions; the others "
                    "would stay at the drawing",
                    id.rank, id.parameters));
  }
  nlohmann::json sd = nlohmann::json::array();
  auto layout = calibration::parameter_layout(mechanism);
  if (!layout) return layout.error();
  for (int i = 0; i < layout->size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    sd.push_back({{"name", layout->names[k]},
                  {"unit", layout->units[k]},
                  {"predicted_sd", i < id.standard_deviation.size() ? id.standard_deviation[i] : 0.0}});
  }
  nlohmann::json summary = {
      {"command", "calibrate plan"},
      {"pkm_version", std::string(pkm_version())},
      {"machine", machine.source},
      {"method", std::string(to_string(job.plan.method))},
      {"poses", count},
      {"angles", std::string(to_string(mechanism.convention()))},
      {"instrument", calibration_instrument_json(job.instrument, prepared->setup)},
      {"box", {{"translation_mm", job.plan.box_mm}, {"angle_deg", job.plan.box_deg}}},
      {"seed", job.plan.seed},
      {"identifiability", calibration_identifiability_json(id)},
      {"predicted_tool_error_mm",
       {{"held_out_poses", prepared->held_out.size()},
        {"rms", prepared->prediction.tool_rms_mm},
        {"p90", prepared->prediction.tool_p90_mm},
        {"max", prepared->prediction.tool_max_mm},
        {"note", "from measurement noise alone; what the plan cannot identify adds its own error"}}},
      {"parameters", sd},
      {"warnings", warnings}};
  if (Status written = write_file_atomically(outputs.staged_path("summary.json"), json_text(summary) + "\n");
      !written)
    return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  CalibrationPlanResult result;
  result.plan = std::move(prepared->plan);
  result.parameters = id.parameters;  // before the prediction `id` is part of moves
  result.prediction = std::move(prepared->prediction);
  result.summary = std::move(summary);
  return result;
}

}  // namespace pkm::pipeline
