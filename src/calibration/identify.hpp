#pragma once
// Identification of a mechanism's geometry from measurements (Smirnov 2019, §5.2.4, eqs. 173–176):
// Levenberg–Marquardt (Eigen's unsupported LevenbergMarquardt module, MINPACK's lmder) from the drawing
// values, on the weighted residuals of residuals.hpp. Honest about what the plan can see: the SVD of the
// weighted, column-scaled Jacobian at the start picks the identifiable directions (identifiability.hpp), the
// solver moves only along them (truncated SVD; the rest stays at the drawing), and a plan that cannot
// identify every parameter is reported as partially identified with the dropped combinations named, never as
// converged. Fewer equations than parameters is an error.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "calibration/calibration_parameters.hpp"
#include "calibration/identifiability.hpp"
#include "calibration/residuals.hpp"
#include "core/result.hpp"
#include "io/measurements.hpp"
#include "machine/mechanism.hpp"

namespace pkm::calibration {

struct IdentifyOptions {
  ResidualOptions residuals;
  IdentifiabilityOptions identifiability;
  int max_evaluations = 400;  ///< residual evaluations of the solver (a Jacobian costs 2 per parameter more)
  /// Stop when an accepted step lowers the sum of squares by less than this fraction (MINPACK ftol)...
  double relative_reduction_tolerance = 1e-10;
  /// ... or when the trust region shrinks below this fraction of the correction (MINPACK xtol).
  double relative_step_tolerance = 1e-10;
  /// MINPACK's initial step bound, relative to the column-scaled correction: large, so that the first step is
  /// Gauss–Newton's (the problem is nearly linear near the drawing); a rejected step shrinks it.
  double initial_step_bound = 1e8;
};

enum class IdentificationStatus {
  identified,            ///< every parameter identified; the solver converged
  partially_identified,  ///< the solver converged on the identifiable combinations; the others were dropped
  not_converged,         ///< the solver stopped without meeting its tolerances
};
const char* to_string(IdentificationStatus status);

/// Residual statistics: weighted (unit variance when the model fits) and raw (mm).
struct ResidualSummary {
  double weighted_rms = 0.0;
  double weighted_max = 0.0;
  double rms_mm = 0.0;
  double max_mm = 0.0;
};

struct IdentificationResult {
  IdentificationStatus status = IdentificationStatus::not_converged;
  std::string solver_message;  ///< why the solver stopped
  int iterations = 0;          ///< accepted Levenberg–Marquardt steps
  int evaluations = 0;         ///< residual evaluations (Jacobians not counted)
  int jacobians = 0;
  ParameterLayout layout;
  Eigen::VectorXd nominal;     ///< the drawing values
  Eigen::VectorXd identified;  ///< physical units, layout order
  ResidualSummary before;
  ResidualSummary after;
  Identifiability at_start;     ///< of the plan at the drawing: chooses the identified subspace
  Identifiability at_solution;  ///< at the identified values: its covariance is the result's
  /// Σ weighted² / (equations − rank): about 1 when the sigmas were right and the model fits.
  double variance_factor = 0.0;
  /// Parameters with no component in the identified subspace: they are exactly the drawing values.
  std::vector<std::string> unchanged_parameters;
  std::vector<GeometryGroup> groups;     ///< the identified values as the mechanism's groups
  std::unique_ptr<Mechanism> mechanism;  ///< the nominal with the identified values
  std::vector<std::string> warnings;     ///< dropped combinations, bad conditioning, the solver

  /// Only a full-rank plan whose solver converged.
  bool converged() const { return status == IdentificationStatus::identified; }
};

/// Identifies the parameters of `nominal` (its geometry_parameters(); wrap it with
/// machine/actuator_offsets.hpp to identify drive offsets too) from `data`. Fails for a mechanism without
/// parameters, fewer equations than parameters, measurements the residuals reject, or a model that has no
/// solution at some pose during the solve.
Result<IdentificationResult> identify(const Mechanism& nominal, const MeasurementSet& data,
                                      const IdentifyOptions& options = {});

/// The residual statistics of `weighted` and `raw`.
ResidualSummary summarize_residuals(const Eigen::VectorXd& weighted, const Eigen::VectorXd& raw);

}  // namespace pkm::calibration
