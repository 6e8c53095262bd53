#pragma once
// The platform's pose from targets fixed to it (Smirnov 2019, eqs. 173–174, generalised): targets known in
// the tool frame t_k and measured in the base frame s_k satisfy s_k = R·t_k + p + noise. The dissertation
// takes p as the centroid of the triangle's vertices (173) and solves (174) for the angles; with any number
// ≥ 3 of targets anywhere on the platform the least-squares pose is the weighted Kabsch/Horn fit: the
// centroids, then R from the SVD of the cross-covariance, and p = s̄ − R·t̄.
#include <Eigen/Core>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "io/measurements.hpp"

namespace pkm::calibration {

/// One target: known on the platform (tool frame), measured in the base frame, with the standard deviation of
/// each measured coordinate.
struct TargetPair {
  Eigen::Vector3d tool_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d measured_mm = Eigen::Vector3d::Zero();
  double sigma_mm = 1.0;
};

using PoseCovariance = Eigen::Matrix<double, 6, 6>;

struct PoseFit {
  Pose pose;  ///< tool point and platform rotation, base frame
  /// Covariance of the fitted pose's error as a twist (δp mm, δω rad, base frame, about the tool point), from
  /// the targets' sigmas to first order: (Σ_k A_kᵀ A_k / σ_k²)⁻¹ with A_k = [I  −[R·t_k]×].
  PoseCovariance covariance = PoseCovariance::Zero();
  double rms_misfit_mm = 0.0;  ///< |s_k − (R·t_k + p)| rms over the targets: how rigid the measured set is
  double max_misfit_mm = 0.0;
};

/// Least-squares pose from ≥ 3 targets that are not collinear (weights 1/σ²). Fails for fewer targets,
/// collinear targets (the rotation about their line is then unknown) or a σ ≤ 0.
Result<PoseFit> fit_pose(const std::vector<TargetPair>& targets);

/// The pairs of one measured pose: fixture positions with their observations. Fails for an observation naming
/// no fixture target.
Result<std::vector<TargetPair>> target_pairs(const std::vector<FixtureTarget>& fixture,
                                             const std::vector<TargetObservation>& observations);

/// Whether the targets' tool-frame positions span a plane (not all on one line or point), relative to their
/// spread: the condition for fit_pose.
bool targets_span_plane(const std::vector<TargetPair>& targets);

}  // namespace pkm::calibration
