#include "pipeline/calibration_setup.hpp"

#include <fmt/format.h>

#include "core/units.hpp"
#include "io/fixture_file.hpp"
#include "io/pose_input.hpp"
#include "machine/actuator_offsets.hpp"
#include "machine/joint_limits.hpp"

namespace pkm::pipeline {

std::optional<CalibrationPlanMethod> calibration_plan_method(std::string_view name) {
  if (name == "seven-pose") return CalibrationPlanMethod::seven_pose;
  if (name == "random") return CalibrationPlanMethod::random;
  if (name == "d-optimal") return CalibrationPlanMethod::d_optimal;
  return std::nullopt;
}

std::string_view to_string(CalibrationPlanMethod method) {
  switch (method) {
    case CalibrationPlanMethod::seven_pose:
      return "seven-pose";
    case CalibrationPlanMethod::random:
      return "random";
    case CalibrationPlanMethod::d_optimal:
      return "d-optimal";
  }
  return "?";
}

Result<std::unique_ptr<Mechanism>> calibration_model(const Machine& machine) {
  auto model = with_actuator_offset_parameters(*machine.mechanism);
  if (!model) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("{}: a {} has no geometry parameters to calibrate ({})", machine.source,
                                  to_string(machine.mechanism->type()), model.error().message));
  }
  return model;
}

Result<calibration::MeasurementSetup> calibration_setup(const CalibrationInstrument& instrument) {
  if (!(instrument.sigma_mm > 0.0) || !std::isfinite(instrument.sigma_mm))
    return make_error(ErrorCode::bad_input,
                      fmt::format("measurement sigma {} mm must be above 0", instrument.sigma_mm));
  if (instrument.ballbar_centre_mm) {
    if (!instrument.fixture_path.empty())
      return make_error(ErrorCode::bad_input,
                        "a ballbar measures no fixture: give the ball's centre or a fixture");
    return calibration::ballbar_setup(*instrument.ballbar_centre_mm, instrument.sigma_mm);
  }
  if (instrument.fixture_path.empty()) {
    if (!(instrument.plate_radius_mm > 0.0))
      return make_error(ErrorCode::bad_input, "the plate's radius must be above 0 mm");
    return calibration::target_setup(instrument.sigma_mm,
                                     calibration::triangular_plate(instrument.plate_radius_mm));
  }
  auto fixture = read_fixture_file(instrument.fixture_path);
  if (!fixture) return fixture.error();
  return calibration::target_setup(instrument.sigma_mm, std::move(*fixture));
}

calibration::PoseFilter calibration_limits_filter(const Machine& machine) {
  return [&machine](const Pose& pose, const ActuatorVector& actuators) {
    return check_actuator_range(machine, actuators).ok() && check_joint_limits(machine, pose).ok() &&
           check_conditioning_limit(machine, pose).ok();
  };
}

Result<calibration::PosePlan> calibration_pose_plan(const Machine& machine, const Mechanism& model,
                                                    const CalibrationPlanSpec& spec,
                                                    const calibration::MeasurementSetup& setup) {
  const calibration::PoseFilter accept = calibration_limits_filter(machine);
  const calibration::PoseBox box{spec.box_mm, rad_from_deg(spec.box_deg)};
  const int n = model.actuator_count();
  if (spec.method == CalibrationPlanMethod::seven_pose) {
    if (spec.poses != 0 && spec.poses != n + 1) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("the seven-pose plan has n + 1 = {} poses on this machine, not {}", n + 1, spec.poses));
    }
    const double change =
        model.actuators_are_angles() ? rad_from_deg(spec.strut_change_mm) : spec.strut_change_mm;
    return calibration::seven_pose_plan(model, change, accept);
  }
  if (spec.poses < 1) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("the {} plan needs a number of poses", to_string(spec.method)));
  }
  if (spec.method == CalibrationPlanMethod::random)
    return calibration::random_plan(model, spec.poses, box, spec.seed, accept);
  calibration::DOptimalOptions options;
  options.candidates = spec.candidates;
  options.box = box;
  options.seed = spec.seed;
  options.accept = accept;
  return calibration::d_optimal_plan(model, setup, spec.poses, options);
}

Result<std::vector<Pose>> calibration_held_out(const Machine& machine, const Mechanism& model,
                                               const CalibrationPlanSpec& spec) {
  if (spec.held_out < 1) return std::vector<Pose>{};
  // Another stream than the plan's, so that no held-out pose is a planned one.
  auto poses = calibration::random_plan(model, spec.held_out, {spec.box_mm, rad_from_deg(spec.box_deg)},
                                        spec.seed ^ 0x5bd1e995ULL, calibration_limits_filter(machine));
  if (!poses) return make_error(poses.error().code, fmt::format("held-out poses: {}", poses.error().message));
  return std::move(poses->poses);
}

std::string calibration_pose_id(int index, int count) {
  const int digits = std::max(2, static_cast<int>(std::to_string(count).size()));
  return fmt::format("P{:0{}}", index + 1, digits);
}

std::string calibration_pose_header(const Mechanism& mechanism) {
  const std::size_t count = user_from_pose(mechanism, mechanism.home()).size();
  if (count == 2) return "x_mm,y_mm";
  if (count == 3) return "x_mm,y_mm,phi_deg";
  return "x_mm,y_mm,z_mm,a1_deg,a2_deg,a3_deg";
}

std::string calibration_pose_fields(const Mechanism& mechanism, const Pose& pose) {
  std::string out;
  for (double value : user_from_pose(mechanism, pose)) {
    if (!out.empty()) out += ',';
    out += fmt::format("{:.9f}", value);
  }
  return out;
}

std::string calibration_reading_header(int count) {
  std::string out;
  for (int j = 1; j <= count; ++j) out += fmt::format(",L{}", j);
  return out;
}

std::string calibration_reading_fields(const Mechanism& mechanism, const ActuatorVector& readings) {
  std::string out;
  for (double value : user_from_actuators(mechanism, readings)) out += fmt::format(",{:.9f}", value);
  return out;
}

nlohmann::json calibration_instrument_json(const CalibrationInstrument& instrument,
                                           const calibration::MeasurementSetup& setup) {
  nlohmann::json json = {{"sigma_mm", setup.sigma_mm}};
  if (setup.kind == calibration::MeasurementKind::ballbar) {
    json["kind"] = "ballbar";
    json["ballbar_centre_mm"] = {setup.ballbar_centre_mm.x(), setup.ballbar_centre_mm.y(),
                                 setup.ballbar_centre_mm.z()};
    return json;
  }
  json["kind"] = "tracker";
  json["fixture"] = instrument.fixture_path.empty()
                        ? fmt::format("triangular plate, radius {:g} mm", instrument.plate_radius_mm)
                        : instrument.fixture_path;
  json["targets"] = setup.fixture.size();
  return json;
}

namespace {

nlohmann::json calibration_combinations_json(
    const std::vector<calibration::ParameterCombination>& combinations) {
  nlohmann::json out = nlohmann::json::array();
  for (const calibration::ParameterCombination& c : combinations)
    out.push_back({{"relative_singular_value", c.relative_singular_value}, {"combination", c.description}});
  return out;
}

// JSON has no infinity: a singular plan's condition number is written as null.
nlohmann::json calibration_finite(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json calibration_identifiability_json(const calibration::Identifiability& identifiability) {
  return {
      {"parameters", identifiability.parameters},
      {"equations", identifiability.equations},
      {"rank", identifiability.rank},
      {"identifiable", identifiability.full_rank()},
      {"condition_number", calibration_finite(identifiability.condition_number)},
      {"identifiable_condition_number", calibration_finite(identifiability.identifiable_condition_number)},
      {"badly_conditioned", identifiability.badly_conditioned},
      {"unidentifiable_combinations", calibration_combinations_json(identifiability.unidentifiable)},
      {"weakest_combinations", calibration_combinations_json(identifiability.weakest)}};
}

Result<CalibrationPrepared> calibration_prepare(const Machine& machine, const CalibrationPlanSpec& spec,
                                                const CalibrationInstrument& instrument) {
  auto model = calibration_model(machine);
  if (!model) return model.error();
  auto setup = calibration_setup(instrument);
  if (!setup) return setup.error();
  auto plan = calibration_pose_plan(machine, **model, spec, *setup);
  if (!plan) return plan.error();
  auto held_out = calibration_held_out(machine, **model, spec);
  if (!held_out) return held_out.error();
  auto prediction = calibration::predict_plan(**model, plan->poses, *setup, *held_out);
  if (!prediction) return prediction.error();
  return CalibrationPrepared{std::move(*model), std::move(*setup), std::move(*plan), std::move(*held_out),
                             std::move(*prediction)};
}

}  // namespace pkm::pipeline
