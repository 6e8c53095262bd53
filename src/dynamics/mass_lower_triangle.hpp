#pragma once
// The mass matrix of the rigid terms (rigid_terms.hpp) as it is gathered body by body: only its lower
// triangle, mirrored once at the end, so that no other 6 × 6 is cleared or copied per evaluation.
#include <Eigen/Core>

namespace pkm::dynamics {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Σ_j G_jᵀ S_j G_j + the platform's, G = [I, −X], X = [arm]×. Bodies that move with a point (the platform,
/// and the struts on fixed base joints, whose S = σ I + κ u uᵀ) add σ GᵀG = σ [I, −X; X, −X²] with
/// −X² = |arm|² I − arm armᵀ: kept as Σ σ, Σ σ arm, Σ σ |arm|² and Σ σ arm armᵀ; their rank-one parts
/// κ j jᵀ, j = (u, arm × u), and other blocks go straight into `lower` (whose upper triangle is never read).
struct MassLowerTriangle {
  double sigma = 0.0, sigma_square = 0.0;  // Σ σ, Σ σ |arm|²
  Eigen::Vector3d sigma_arm = Eigen::Vector3d::Zero();
  Matrix6 lower;  // only the lower triangle is set, added to and read

  MassLowerTriangle() { clear(); }

  /// Back to no bodies (a workspace's triangle, reused).
  void clear() {
    sigma = sigma_square = 0.0;
    sigma_arm.setZero();
    for (int c = 0; c < 6; ++c) {
      for (int r = c; r < 6; ++r) lower(r, c) = 0.0;
    }
  }

  /// σ GᵀG for a body whose velocity is that of the point at `arm` (the platform: σ = m).
  void add_point(double s, const Eigen::Vector3d& arm) {
    sigma += s;
    const Eigen::Vector3d weighted = s * arm;
    sigma_arm += weighted;
    sigma_square += weighted.dot(arm);
    for (int c = 0; c < 3; ++c) {
      for (int r = c; r < 3; ++r) lower(3 + r, 3 + c) -= weighted[r] * arm[c];  // −X² = … − arm armᵀ
    }
  }

  /// Adds the point bodies' sums into `lower`, which is then the lower triangle of the whole matrix (what
  /// the fixed-size Cholesky reads). Once, after the last body.
  void fold_sums() {
    for (int k = 0; k < 3; ++k) {
      lower(k, k) += sigma;
      lower(3 + k, 3 + k) += sigma_square;
    }
    // The lower left block is X = [Σ σ arm]× (the upper right −X = Xᵀ); its diagonal is zero.
    lower(4, 0) += sigma_arm[2];
    lower(5, 0) += -sigma_arm[1];
    lower(3, 1) += -sigma_arm[2];
    lower(5, 1) += sigma_arm[0];
    lower(3, 2) += sigma_arm[1];
    lower(4, 2) += -sigma_arm[0];
  }

  /// The whole symmetric matrix into `m` (a 6 × 6, fixed or of run-time size), entry by entry, after
  /// fold_sums().
  template <class Matrix>
  void write_full(Matrix& m) const {
    m.resize(6, 6);
    for (int c = 0; c < 6; ++c) {
      for (int r = c; r < 6; ++r) m(r, c) = m(c, r) = lower(r, c);
    }
  }
};

}  // namespace pkm::dynamics
