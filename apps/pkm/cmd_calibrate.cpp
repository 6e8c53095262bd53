// pkm calibrate plan | simulate | identify: the subcommands (cmd_calibrate_*.cpp) and the options they share.
#include "cmd_calibrate.hpp"

#include <fmt/format.h>

#include <iostream>

#include "commands.hpp"
#include "io/pose_input.hpp"
#include "number_options.hpp"
#include "pipeline/calibration_checks.hpp"

namespace pkm::cli {

void add_calibrate_instrument_options(CLI::App& cmd, pipeline::CalibrationInstrument& instrument,
                                      CalibrateInstrumentText& text) {
  cmd.add_option(
      "--fixture", instrument.fixture_path,
      "fixture file: the tracker's targets on the platform (CSV target,x,y,z, tool frame, mm); default: "
      "the dissertation's triangular plate");
  cmd.add_option("--plate-radius-mm", instrument.plate_radius_mm,
                 "radius of the default triangular plate's vertices about the tool point, mm")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationPlateRadiusMm)));
  cmd.add_option("--ballbar-centre", text.ballbar_centre,
                 "measure with a ballbar from the tool point to a ball at X,Y,Z (base frame, mm) instead");
  cmd.add_option("--sigma-mm", instrument.sigma_mm,
                 "standard deviation of each measured coordinate or length, mm")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationSigmaMm)));
}

Result<pipeline::CalibrationInstrument> calibrate_instrument(pipeline::CalibrationInstrument instrument,
                                                             const CalibrateInstrumentText& text) {
  if (text.ballbar_centre.empty()) return instrument;
  auto centre = parse_number_list(text.ballbar_centre, "--ballbar-centre");
  if (!centre) return centre.error();
  if (centre->size() != 3) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--ballbar-centre: expected 3 numbers x,y,z (mm), got {}", centre->size()));
  }
  instrument.ballbar_centre_mm = Eigen::Vector3d((*centre)[0], (*centre)[1], (*centre)[2]);
  return instrument;
}

void add_calibrate_plan_options(CLI::App& cmd, pipeline::CalibrationPlanSpec& spec, std::string& method) {
  cmd.add_option("--method", method, "how the poses are chosen: seven-pose, random or d-optimal")
      ->capture_default_str();
  spec.poses = 12;
  cmd.add_option("--poses", spec.poses, "poses to measure (seven-pose: n + 1 unless given)")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationPoses)));
  cmd.add_option("--box-mm", spec.box_mm, "random and d-optimal poses: ± this on x, y, z around home, mm")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationBoxMm)));
  cmd.add_option("--box-deg", spec.box_deg, "... and ± this on each angle, deg")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationBoxDeg)));
  cmd.add_option("--strut-change-mm", spec.strut_change_mm,
                 "seven-pose: each actuator's change from home, mm (deg for turning actuators)")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationStrutChangeMm)));
  cmd.add_option("--candidates", spec.candidates, "d-optimal: random poses to choose from")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationCandidates)));
  cmd.add_option("--held-out", spec.held_out, "random poses where the tool error is predicted or judged")
      ->capture_default_str()
      ->check(number_in(number_range(pipeline::kCalibrationHeldOut)));
  cmd.add_option("--seed", spec.seed, "seed of the random draws (the same seed gives the same run)")
      ->capture_default_str()
      ->check(number_in({0.0, 1e15, true, true, "", true}));
}

Result<pipeline::CalibrationPlanSpec> calibrate_plan_spec(pipeline::CalibrationPlanSpec spec,
                                                          const std::string& method, bool poses_given) {
  auto parsed = pipeline::calibration_plan_method(method);
  if (!parsed) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--method: expected seven-pose, random or d-optimal, got '{}'", method));
  }
  spec.method = *parsed;
  if (spec.method == pipeline::CalibrationPlanMethod::seven_pose && !poses_given) spec.poses = 0;
  return spec;
}

void print_calibrate_identifiability(const calibration::Identifiability& id) {
  std::cout << fmt::format(
      "  parameters     {} from {} equations: rank {}{}\n", id.parameters, id.equations, id.rank,
      id.full_rank() ? " (every parameter identifiable)" : " (NOT every parameter identifiable)");
  std::cout << fmt::format("  condition      {:.4g} (identifiable directions; all: {:.4g})\n",
                           id.identifiable_condition_number, id.condition_number);
  // A handful names the kind of deficiency; summary.json lists every combination.
  constexpr std::size_t kShown = 5;
  for (std::size_t k = 0; k < id.unidentifiable.size() && k < kShown; ++k) {
    const calibration::ParameterCombination& c = id.unidentifiable[k];
    std::cout << fmt::format("  unidentifiable {} (σ/σmax {:.2g})\n", c.description,
                             c.relative_singular_value);
  }
  if (id.unidentifiable.size() > kShown)
    std::cout << fmt::format("  unidentifiable … {} more (summary.json lists them)\n",
                             id.unidentifiable.size() - kShown);
  for (const calibration::ParameterCombination& c : id.weakest)
    std::cout << fmt::format("  weakest        {} (σ/σmax {:.2g})\n", c.description,
                             c.relative_singular_value);
}

void add_calibrate_command(CLI::App& app, int& exit_code) {
  auto* calibrate = app.add_subcommand(
      "calibrate",
      "calibration of the machine's geometry: plan the poses, simulate, identify from measurements");
  calibrate->require_subcommand(1);
  add_calibrate_plan_command(*calibrate, exit_code);
  add_calibrate_simulate_command(*calibrate, exit_code);
  add_calibrate_identify_command(*calibrate, exit_code);
}

}  // namespace pkm::cli
