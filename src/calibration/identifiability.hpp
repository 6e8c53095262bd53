#pragma once
// What a measurement plan can identify (Smirnov 2019, §5.2.4; its 7 × 7 systems per strut are exactly
// determined and say nothing of their conditioning): the SVD J = U·Σ·Vᵀ of the weighted (unit-variance),
// column-scaled identification Jacobian (parameter_jacobian.hpp). Right singular vectors whose singular
// value is below a relative threshold are combinations of parameters the data cannot see; the
// identification keeps them at the drawing values (truncated SVD) and names them by their largest
// components. The covariance of the identified parameters is (JᵀJ)⁺ on the kept directions (the weights
// already carry σ², so the a-priori variance factor is 1).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "calibration/calibration_parameters.hpp"

namespace pkm::calibration {

/// A direction in the scaled parameter space, described by its largest components.
struct ParameterCombination {
  double relative_singular_value = 0.0;                    ///< σ_i / σ_max
  std::vector<std::pair<std::string, double>> components;  ///< (parameter, component), largest first
  std::string description;                                 ///< e.g. "+0.71 A3.z −0.70 dL3 (strut 3)"
};

struct IdentifiabilityOptions {
  /// Directions with σ_i / σ_max below this are not identifiable: dropped, their parameters stay at the
  /// drawing. Above the noise of the finite-difference Jacobian (~1e-10 relative), below any plan worth
  /// measuring.
  double relative_threshold = 1e-7;
  /// Above this condition number of the kept directions a warning says the plan is badly conditioned: the
  /// weakest combination's error is that many times the measurement noise (relative to the strongest).
  double warn_condition_number = 1e4;
  int named_components = 4;  ///< components named per combination (those ≥ 1/4 of its largest)
  int weakest_named = 3;     ///< kept combinations named, weakest first
};

struct Identifiability {
  int parameters = 0;
  int equations = 0;
  int rank = 0;                     ///< directions kept
  Eigen::VectorXd singular_values;  ///< all `parameters`, descending (zeros where equations < parameters)
  Eigen::MatrixXd right_vectors;    ///< parameters × parameters, scaled space, columns as singular_values
  double condition_number = 0.0;    ///< σ_max / σ_min over every direction (infinite when σ_min = 0)
  double identifiable_condition_number = 0.0;        ///< σ_max / σ_rank: of the kept directions
  std::vector<ParameterCombination> unidentifiable;  ///< dropped directions, strongest first
  std::vector<ParameterCombination> weakest;         ///< kept directions, weakest first
  Eigen::MatrixXd covariance;                        ///< physical units, rank-truncated (JᵀJ)⁺
  Eigen::VectorXd standard_deviation;                ///< √diag(covariance), per parameter, physical units
  std::vector<std::string> warnings;
  bool badly_conditioned = false;  ///< identifiable_condition_number > warn_condition_number

  bool full_rank() const { return rank == parameters; }
  /// The kept right singular vectors (parameters × rank): the subspace an identification moves in.
  Eigen::MatrixXd identifiable_basis() const { return right_vectors.leftCols(rank); }
};

/// The diagnostics of `scaled_jacobian` (equations × layout.size()).
Identifiability analyse_identifiability(const Eigen::MatrixXd& scaled_jacobian, const ParameterLayout& layout,
                                        const IdentifiabilityOptions& options = {});

/// `direction` (scaled space, layout.size()) described by its largest components.
ParameterCombination describe_combination(const Eigen::VectorXd& direction, double relative_singular_value,
                                          const ParameterLayout& layout, int named_components);

}  // namespace pkm::calibration
