#pragma once
// Least-squares fitting of the strut-law models of strut_law_piece.hpp to inverse-kinematics samples
// (Smirnov 2019, Fig. 167): the coefficients come from the samples, not from the mechanism's geometry, so
// the same code serves every mechanism, and a model that does not suit a mechanism or a segment shows up as
// a large fit error (strut_laws.cpp checks it against IK away from the fit nodes).
#include <Eigen/Core>

#include "interpolation/methods/strut_law_piece.hpp"

namespace pkm::interpolation {

/// Chebyshev nodes of the first kind on [−1, 1], u_k = cos((2k + 1)π/(2n)): interpolation there comes close
/// to the best polynomial approximation, with none of the end oscillation of equally spaced nodes.
Eigen::VectorXd law_fit_chebyshev_nodes(int count);
/// Chebyshev–Lobatto nodes (the extrema of T_{n−1}) on [−1, 1], u_k = cos(kπ/(n − 1)), both ends included:
/// as good for interpolation as the nodes above, and a polynomial through them meets exact IK at both ends
/// of its piece, so that neighbouring pieces join without a step (count 1: the middle).
Eigen::VectorXd law_fit_lobatto_nodes(int count);

/// Coefficients of `model` (not exact) for every actuator at once: column j of `values` holds actuator j at
/// the nodes `u` (rows), the result's column j its `stride` coefficients (strut_law_piece.hpp). The sqrt
/// models fit L² (eqs. 149, 150), the polynomial L itself (eq. 151). At least `stride` distinct nodes.
Eigen::MatrixXd law_fit_coefficients(LawModel model, const Eigen::VectorXd& u, double angle_per_u, int stride,
                                     const Eigen::MatrixXd& values);

}  // namespace pkm::interpolation
