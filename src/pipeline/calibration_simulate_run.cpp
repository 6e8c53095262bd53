// `pkm calibrate simulate` (calibration_run.hpp): Monte-Carlo trials of the whole calibration on perturbed
// machines (trials.csv, summary.json) and, if asked, one simulated measurement file that `pkm calibrate
// identify` reads like a real one, with the true parameters it should recover.
#include <fmt/format.h>

#include <filesystem>
#include <iterator>

#include "io/atomic_file.hpp"
#include "io/fixture_file.hpp"
#include "io/json_text.hpp"
#include "io/measurement_file.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/calibration_checks.hpp"
#include "pipeline/calibration_run.hpp"
#include "pipeline/calibration_setup.hpp"

namespace pkm::pipeline {
namespace {

std::string calsim_trials_csv(const calibration::MonteCarloSummary& mc, std::uint64_t seed) {
  std::string csv =
      "trial,seed,ok,status,rank,condition_number,iterations,parameter_error_max_mm,parameter_error_rms_mm,"
      "held_out_max_mm,held_out_rms_mm,error\n";
  auto out = std::back_inserter(csv);
  for (std::size_t t = 0; t < mc.results.size(); ++t) {
    const calibration::TrialResult& r = mc.results[t];
    std::string error = r.error;
    for (char& c : error)
      if (c == ',' || c == '\n' || c == '\r') c = ';';  // one field of one row
    fmt::format_to(out, "{},{},{},{},{},{:.6g},{},{:.9g},{:.9g},{:.9g},{:.9g},{}\n", t + 1,
                   calibration::trial_seed(seed, static_cast<int>(t)), r.ok ? 1 : 0,
                   r.ok ? calibration::to_string(r.status) : "failed", r.rank, r.condition_number,
                   r.iterations, r.parameter_error_max_mm, r.parameter_error_rms_mm, r.held_out_max_mm,
                   r.held_out_rms_mm, error);
  }
  return csv;
}

nlohmann::json calsim_distribution(const calibration::TrialDistribution& d) {
  return {{"median", d.median}, {"p90", d.p90}};
}

// One machine drawn from the seed, measured along the plan: the measurement file, its fixture beside it, and
// DIR/true_parameters.csv.
Status calsim_write_measurements(const Machine& machine, const Mechanism& model,
                                 const CalibrationSimulateJob& job, const calibration::PosePlan& plan,
                                 const calibration::MeasurementSetup& setup, OutputSet& outputs) {
  auto layout = calibration::parameter_layout(model);
  if (!layout) return layout.error();
  std::mt19937_64 rng(job.plan.seed);
  const Eigen::VectorXd nominal = calibration::parameter_vector(layout->groups);
  const Eigen::VectorXd truth_values =
      calibration::perturbed_parameters(*layout, nominal, {job.joint_error_mm, job.offset_error_mm}, rng);
  auto truth = calibration::mechanism_with_parameters(model, *layout, truth_values);
  if (!truth) return truth.error();
  auto data =
      calibration::simulate_measurements(model, **truth, plan.poses, setup, job.noise ? &rng : nullptr);
  if (!data) return data.error();
  const int count = static_cast<int>(data->poses.size());
  for (int p = 0; p < count; ++p) data->poses[static_cast<std::size_t>(p)].id = calibration_pose_id(p, count);

  const std::filesystem::path file(job.measurements_path);
  MeasurementWriteOptions write;
  write.actuators_are_angles = model.actuators_are_angles();
  write.machine_file = machine.source;
  write.notes = {
      fmt::format("simulated by pkm calibrate simulate: {} plan, seed {}, joints ±{} mm, drive offsets ±{} "
                  "mm, {}",
                  to_string(job.plan.method), job.plan.seed, job.joint_error_mm, job.offset_error_mm,
                  job.noise ? fmt::format("noise σ {} mm", setup.sigma_mm) : std::string("no noise")),
      fmt::format("true parameters: {}",
                  (std::filesystem::path(job.out_directory) / "true_parameters.csv").string())};
  if (setup.kind == calibration::MeasurementKind::targets && !job.instrument.fixture_path.empty()) {
    // The given fixture, named relative to the file as the reader resolves it.
    const std::filesystem::path folder = std::filesystem::absolute(file).parent_path();
    write.fixture_file =
        std::filesystem::absolute(job.instrument.fixture_path).lexically_proximate(folder).generic_string();
  } else if (setup.kind == calibration::MeasurementKind::targets) {
    // The default plate as a fixture file beside the file, so that the pair moves together.
    const std::string fixture_name = file.stem().string() + "_fixture.csv";
    write.fixture_file = fixture_name;
    auto staged_fixture = outputs.stage_file((file.parent_path() / fixture_name).string());
    if (!staged_fixture) return staged_fixture.error();
    if (Status written = write_file_atomically(*staged_fixture, fixture_file_text(setup.fixture)); !written)
      return written;
  }
  auto text = measurement_file_text(*data, write);
  if (!text) return text.error();
  auto staged = outputs.stage_file(job.measurements_path);
  if (!staged) return staged.error();
  if (Status written = write_file_atomically(*staged, *text); !written) return written;

  std::string csv = "name,unit,nominal,true,change\n";
  for (int i = 0; i < layout->size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    fmt::format_to(std::back_inserter(csv), "{},{},{},{},{}\n", layout->names[k], layout->units[k],
                   nominal[i], truth_values[i], truth_values[i] - nominal[i]);
  }
  return write_file_atomically(outputs.staged_path("true_parameters.csv"), csv);
}

}  // namespace

Result<CalibrationSimulateResult> calibration_simulate(const Machine& machine,
                                                       const CalibrationSimulateJob& job) {
  if (Status valid = check_calibration_simulate_job(job); !valid) return valid.error();
  auto prepared = calibration_prepare(machine, job.plan, job.instrument);
  if (!prepared) return prepared.error();

  calibration::TrialSetup trial;
  trial.plan = prepared->plan.poses;
  trial.setup = prepared->setup;
  trial.held_out = prepared->held_out;
  trial.perturbation = {job.joint_error_mm, job.offset_error_mm};
  CalibrationSimulateResult result;
  result.monte_carlo = calibration::monte_carlo(*prepared->model, trial, job.trials, job.plan.seed);
  result.parameters = prepared->prediction.identifiability.parameters;
  result.plan_poses = static_cast<int>(prepared->plan.poses.size());
  const calibration::MonteCarloSummary& mc = result.monte_carlo;

  OutputSet outputs{"calibrate simulate"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  if (Status written =
          write_file_atomically(outputs.staged_path("trials.csv"), calsim_trials_csv(mc, job.plan.seed));
      !written)
    return written.error();
  if (!job.measurements_path.empty()) {
    if (Status written = calsim_write_measurements(machine, *prepared->model, job, prepared->plan,
                                                   prepared->setup, outputs);
        !written)
      return written.error();
  }
  std::vector<std::string> warnings = prepared->prediction.identifiability.warnings;
  if (!prepared->prediction.identifiability.full_rank()) {
    warnings.insert(warnings.begin(),
                    fmt::format("not identifiable: the plan determines {} of {} parameter directions",
                                prepared->prediction.identifiability.rank, result.parameters));
  }
  if (mc.failed > 0) {
    for (const calibration::TrialResult& r : mc.results) {
      if (r.ok) continue;
      warnings.push_back(fmt::format("{} of {} trials failed; the first: {}", mc.failed, mc.trials, r.error));
      break;
    }
  }
  if (mc.not_converged > 0)
    warnings.push_back(fmt::format("{} of {} identifications did not converge", mc.not_converged, mc.trials));
  nlohmann::json summary = {
      {"command", "calibrate simulate"},
      {"pkm_version", std::string(pkm_version())},
      {"machine", machine.source},
      {"method", std::string(to_string(job.plan.method))},
      {"poses", result.plan_poses},
      {"parameters", result.parameters},
      {"instrument", calibration_instrument_json(job.instrument, prepared->setup)},
      {"perturbation", {{"joint_error_mm", job.joint_error_mm}, {"offset_error_mm", job.offset_error_mm}}},
      {"seed", job.plan.seed},
      {"trials", mc.trials},
      {"failed", mc.failed},
      {"not_converged", mc.not_converged},
      {"held_out_poses", prepared->held_out.size()},
      {"held_out_rms_mm", calsim_distribution(mc.held_out_rms_mm)},
      {"held_out_max_mm", calsim_distribution(mc.held_out_max_mm)},
      {"parameter_error_max_mm", calsim_distribution(mc.parameter_error_max_mm)},
      {"parameter_error_rms_mm", calsim_distribution(mc.parameter_error_rms_mm)},
      {"mean_condition_number", mc.mean_condition_number},
      {"predicted_tool_rms_mm", prepared->prediction.tool_rms_mm},
      {"identifiability", calibration_identifiability_json(prepared->prediction.identifiability)},
      {"warnings", warnings}};
  if (!job.measurements_path.empty()) {
    summary["measurements"] = {
        {"file", job.measurements_path}, {"true_parameters", "true_parameters.csv"}, {"noise", job.noise}};
  }
  if (Status written = write_file_atomically(outputs.staged_path("summary.json"), json_text(summary) + "\n");
      !written)
    return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.summary = std::move(summary);
  return result;
}

}  // namespace pkm::pipeline
