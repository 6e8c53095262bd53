#include "calibration/simulate.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "calibration/statistics.hpp"

namespace pkm::calibration {

namespace {

// Forward kinematics of the judged machines: to round-off, the errors judged are 1e-9 mm and up.
const FkOptions kJudgeFk{1e-12, 60, 1e-13, true};

TrialDistribution distribution(const std::vector<double>& values) {
  return {quantile(values, 0.5), quantile(values, 0.9)};
}

// A model so far off that it has no forward solution at a held-out pose is a result, not a failure: that
// pose's error counts as infinite. The true machine must solve (it was drawn close to the drawing).
Status held_out_errors(const Mechanism& nominal, const Mechanism& truth, const Mechanism& identified,
                       const std::vector<Pose>& held_out, TrialResult& result) {
  std::vector<double> errors;
  for (std::size_t p = 0; p < held_out.size(); ++p) {
    auto readings = nominal.inverse(held_out[p]);
    if (!readings) {
      return make_error(readings.error().code,
                        fmt::format("held-out pose {}: {}", p + 1, readings.error().message));
    }
    auto true_pose = truth.forward(*readings, held_out[p], kJudgeFk);
    if (!true_pose) {
      return make_error(true_pose.error().code, fmt::format("held-out pose {}: the true machine: {}", p + 1,
                                                            true_pose.error().message));
    }
    auto model_pose = identified.forward(*readings, true_pose->pose, kJudgeFk);
    if (!model_pose) {
      ++result.held_out_unsolved;
      errors.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    errors.push_back((true_pose->pose.position_mm - model_pose->pose.position_mm).norm());
  }
  result.held_out_rms_mm = root_mean_square(errors);
  result.held_out_max_mm = errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end());
  return ok_status();
}

}  // namespace

std::uint64_t trial_seed(std::uint64_t seed, int index) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(index) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

Eigen::VectorXd perturbed_parameters(const ParameterLayout& layout, const Eigen::VectorXd& nominal,
                                     const PerturbationOptions& options, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd values = nominal;
  for (int i = 0; i < layout.size(); ++i) {
    const bool offset = layout.group_keys[static_cast<std::size_t>(i)] == "actuator_offsets";
    const double amplitude_mm = offset ? options.offset_error_mm : options.joint_error_mm;
    values[i] += unit(rng) * amplitude_mm / layout.scale[i];
  }
  return values;
}

TrialResult simulate_trial(const Mechanism& nominal, const TrialSetup& setup, std::uint64_t seed) {
  TrialResult result;
  auto fail = [&](const std::string& why) {
    result.error = why;
    return result;
  };
  auto layout = parameter_layout(nominal);
  if (!layout) return fail(layout.error().message);
  std::mt19937_64 rng(seed);
  const Eigen::VectorXd true_values =
      perturbed_parameters(*layout, parameter_vector(layout->groups), setup.perturbation, rng);
  auto truth = mechanism_with_parameters(nominal, *layout, true_values);
  if (!truth) return fail(truth.error().message);
  auto data = simulate_measurements(nominal, **truth, setup.plan, setup.setup, &rng);
  if (!data) return fail(data.error().message);
  auto identified = identify(nominal, *data, setup.identify);
  if (!identified) return fail(identified.error().message);

  result.status = identified->status;
  result.rank = identified->at_start.rank;
  result.condition_number = identified->at_start.identifiable_condition_number;
  result.iterations = identified->iterations;
  result.predicted_sd = identified->at_solution.standard_deviation;
  // The error over the scaled parameters, projected on the identified subspace when some were dropped.
  Eigen::VectorXd error = (identified->identified - true_values).cwiseQuotient(layout->scale);
  if (!identified->at_start.full_rank()) {
    const Eigen::MatrixXd basis = identified->at_start.identifiable_basis();
    error = basis * (basis.transpose() * error);
  }
  result.parameter_error = error;
  result.parameter_error_max_mm = error.size() > 0 ? error.cwiseAbs().maxCoeff() : 0.0;
  result.parameter_error_rms_mm =
      error.size() > 0 ? std::sqrt(error.squaredNorm() / static_cast<double>(error.size())) : 0.0;
  if (auto ok = held_out_errors(nominal, **truth, *identified->mechanism, setup.held_out, result); !ok) {
    return fail(ok.error().message);
  }
  result.ok = true;
  return result;
}

MonteCarloSummary monte_carlo(const Mechanism& nominal, const TrialSetup& setup, int trials,
                              std::uint64_t seed) {
  MonteCarloSummary summary;
  summary.trials = trials;
  summary.results.resize(static_cast<std::size_t>(std::max(trials, 0)));
  tbb::parallel_for(0, trials, [&](int t) {
    summary.results[static_cast<std::size_t>(t)] = simulate_trial(nominal, setup, trial_seed(seed, t));
  });
  std::vector<double> held_rms, held_max, par_max, par_rms;
  double condition_sum = 0.0;
  for (const TrialResult& r : summary.results) {
    if (!r.ok) {
      ++summary.failed;
      continue;
    }
    if (r.status == IdentificationStatus::not_converged) ++summary.not_converged;
    if (r.held_out_unsolved > 0) ++summary.unusable;
    held_rms.push_back(r.held_out_rms_mm);
    held_max.push_back(r.held_out_max_mm);
    par_max.push_back(r.parameter_error_max_mm);
    par_rms.push_back(r.parameter_error_rms_mm);
    condition_sum += r.condition_number;
  }
  summary.held_out_rms_mm = distribution(held_rms);
  summary.held_out_max_mm = distribution(held_max);
  summary.parameter_error_max_mm = distribution(par_max);
  summary.parameter_error_rms_mm = distribution(par_rms);
  const int succeeded = trials - summary.failed;
  summary.mean_condition_number = succeeded > 0 ? condition_sum / succeeded : 0.0;
  return summary;
}

}  // namespace pkm::calibration
