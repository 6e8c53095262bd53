#include "calibration/pose_fit.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <cmath>

namespace pkm::calibration {

namespace {

// Below this ratio of the second to the largest singular value of the centred targets they count as
// collinear: the rotation about their line would rest on round-off.
constexpr double kCollinearRatio = 1e-9;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

struct Centroids {
  Eigen::Vector3d tool = Eigen::Vector3d::Zero();
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
};

Centroids weighted_centroids(const std::vector<TargetPair>& targets) {
  Centroids c;
  double total = 0.0;
  for (const TargetPair& t : targets) {
    const double w = 1.0 / (t.sigma_mm * t.sigma_mm);
    c.tool += w * t.tool_mm;
    c.measured += w * t.measured_mm;
    total += w;
  }
  c.tool /= total;
  c.measured /= total;
  return c;
}

}  // namespace

bool targets_span_plane(const std::vector<TargetPair>& targets) {
  if (targets.size() < 3) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const TargetPair& t : targets) mean += t.tool_mm;
  mean /= static_cast<double>(targets.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const TargetPair& t : targets) scatter += (t.tool_mm - mean) * (t.tool_mm - mean).transpose();
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(scatter).singularValues();
  // Singular values of the scatter are squared spreads: compare their square roots.
  return s[0] > 0.0 && std::sqrt(s[1] / s[0]) > kCollinearRatio;
}

Result<PoseFit> fit_pose(const std::vector<TargetPair>& targets) {
  if (targets.size() < 3) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("a pose needs at least 3 targets, got {}", targets.size()));
  }
  for (const TargetPair& t : targets) {
    if (!(t.sigma_mm > 0.0) || !std::isfinite(t.sigma_mm)) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("a target's sigma is {} mm; it must be > 0", t.sigma_mm));
    }
  }
  if (!targets_span_plane(targets)) {
    return make_error(ErrorCode::singular,
                      "the targets lie on one line: the rotation about that line cannot be measured");
  }
  // Horn/Kabsch: the rotation maximising Σ w (s_k − s̄)·R(t_k − t̄) is V·diag(1, 1, det)·Uᵀ for H = U S Vᵀ.
  const Centroids c = weighted_centroids(targets);
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (const TargetPair& t : targets) {
    const double w = 1.0 / (t.sigma_mm * t.sigma_mm);
    h += w * (t.tool_mm - c.tool) * (t.measured_mm - c.measured).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  if (!(svd.singularValues()[1] > kCollinearRatio * svd.singularValues()[0])) {
    return make_error(
        ErrorCode::singular,
        "the measured targets lie on one line: the rotation about that line cannot be measured");
  }
  PoseFit fit;
  fit.pose.rotation = svd.matrixV() * d * svd.matrixU().transpose();
  fit.pose.position_mm = c.measured - fit.pose.rotation * c.tool;

  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  double sum_squares = 0.0;
  for (const TargetPair& t : targets) {
    const Eigen::Vector3d arm = fit.pose.rotation * t.tool_mm;
    Eigen::Matrix<double, 3, 6> a;
    a << Eigen::Matrix3d::Identity(), -cross_matrix(arm);
    information += a.transpose() * a / (t.sigma_mm * t.sigma_mm);
    const double misfit = (t.measured_mm - arm - fit.pose.position_mm).norm();
    sum_squares += misfit * misfit;
    fit.max_misfit_mm = std::max(fit.max_misfit_mm, misfit);
  }
  fit.rms_misfit_mm = std::sqrt(sum_squares / static_cast<double>(targets.size()));
  fit.covariance = information.ldlt().solve(PoseCovariance::Identity());
  return fit;
}

Result<std::vector<TargetPair>> target_pairs(const std::vector<FixtureTarget>& fixture,
                                             const std::vector<TargetObservation>& observations) {
  std::vector<TargetPair> pairs;
  pairs.reserve(observations.size());
  for (const TargetObservation& o : observations) {
    if (o.target < 0 || o.target >= static_cast<int>(fixture.size())) {
      return make_error(ErrorCode::bad_input, fmt::format("an observation names target {} of a fixture of {}",
                                                          o.target + 1, fixture.size()));
    }
    pairs.push_back({fixture[static_cast<std::size_t>(o.target)].position_mm, o.position_mm, o.sigma_mm});
  }
  return pairs;
}

}  // namespace pkm::calibration
