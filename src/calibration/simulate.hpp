#pragma once
// The calibration simulated end to end (Smirnov 2019, §5.2.4: vertices measured to 0.01 mm gave
// the joints to 0.03 mm): a true machine is drawn around the drawing, measured along a plan with noise
// (synthetic_measurements.hpp), identified (identify.hpp), and judged by its parameter errors and by the
// tool-point error at held-out poses: |FK_true(L) − FK_identified(L)| with L = IK_nominal(P), what
// compensation with the identified model would leave. Monte-Carlo trials run in parallel (oneTBB), each with
// its own seed derived from the run's seed and its index, so a run is reproducible whatever the threads do.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "calibration/identify.hpp"
#include "calibration/synthetic_measurements.hpp"

namespace pkm::calibration {

/// How far the true machine is from the drawing: uniform ± on every parameter.
struct PerturbationOptions {
  double joint_error_mm = 0.1;   ///< joint coordinates (other units: this many mm at the parameter's scale)
  double offset_error_mm = 0.1;  ///< drive offsets (group "actuator_offsets")
};

/// Drawing values `nominal` perturbed as `options` says.
Eigen::VectorXd perturbed_parameters(const ParameterLayout& layout, const Eigen::VectorXd& nominal,
                                     const PerturbationOptions& options, std::mt19937_64& rng);

struct TrialSetup {
  std::vector<Pose> plan;      ///< poses measured
  MeasurementSetup setup;      ///< what is measured there, and σ
  std::vector<Pose> held_out;  ///< poses the identified model is judged at
  PerturbationOptions perturbation;
  IdentifyOptions identify;
};

struct TrialResult {
  bool ok = false;
  std::string error;  ///< why the trial failed (!ok)
  IdentificationStatus status = IdentificationStatus::not_converged;
  int rank = 0;
  double condition_number =
      0.0;  ///< of the identified directions (Identifiability::identifiable_condition_number)
  int iterations = 0;
  /// identified − true over the scaled parameters (mm); with dropped combinations, only its component in the
  /// identified subspace (the dropped ones are not estimated at all).
  Eigen::VectorXd parameter_error;
  double parameter_error_max_mm = 0.0;
  double parameter_error_rms_mm = 0.0;
  double held_out_max_mm = 0.0;  ///< infinite where the identified model has no forward solution
  double held_out_rms_mm = 0.0;  ///< infinite where the identified model has no forward solution
  int held_out_unsolved = 0;     ///< held-out poses where the identified model has no forward solution
  /// The identification's predicted standard deviation per parameter (physical units).
  Eigen::VectorXd predicted_sd;
};

/// One trial: true machine, measurements and noise all from `seed`.
TrialResult simulate_trial(const Mechanism& nominal, const TrialSetup& setup, std::uint64_t seed);

/// Median and 90th percentile of a quantity over the trials that succeeded (infinite values sort last).
struct TrialDistribution {
  double median = 0.0;
  double p90 = 0.0;
};

struct MonteCarloSummary {
  int trials = 0;
  int failed = 0;         ///< trials that produced no identification (the reasons are in `results`)
  int not_converged = 0;  ///< identifications whose solver did not converge
  int unusable = 0;       ///< identified models without a forward solution at some held-out pose
  TrialDistribution held_out_rms_mm;
  TrialDistribution held_out_max_mm;
  TrialDistribution parameter_error_max_mm;
  TrialDistribution parameter_error_rms_mm;
  double mean_condition_number = 0.0;
  std::vector<TrialResult> results;  ///< in trial order
};

/// `trials` trials in parallel; trial t uses the seed trial_seed(seed, t).
MonteCarloSummary monte_carlo(const Mechanism& nominal, const TrialSetup& setup, int trials,
                              std::uint64_t seed);

/// The seed of trial `index` of a run seeded `seed` (SplitMix64: neighbouring indices give unrelated
/// streams).
std::uint64_t trial_seed(std::uint64_t seed, int index);

}  // namespace pkm::calibration
