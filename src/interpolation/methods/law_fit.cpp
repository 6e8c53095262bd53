#include "interpolation/methods/law_fit.hpp"

#include <Eigen/QR>
#include <cmath>
#include <numbers>

namespace pkm::interpolation {

Eigen::VectorXd law_fit_chebyshev_nodes(int count) {
  Eigen::VectorXd u(count);
  for (int k = 0; k < count; ++k) u[k] = std::cos((2.0 * k + 1.0) * std::numbers::pi / (2.0 * count));
  return u;
}

Eigen::VectorXd law_fit_lobatto_nodes(int count) {
  if (count == 1) return Eigen::VectorXd::Zero(1);
  Eigen::VectorXd u(count);
  for (int k = 0; k < count; ++k) u[k] = std::cos(k * std::numbers::pi / (count - 1));
  u[0] = 1.0;  // exactly, whatever the rounding of cos
  u[count - 1] = -1.0;
  return u;
}

Eigen::MatrixXd law_fit_coefficients(LawModel model, const Eigen::VectorXd& u, double angle_per_u, int stride,
                                     const Eigen::MatrixXd& values) {
  const Eigen::Index nodes = u.size();
  Eigen::MatrixXd basis(nodes, stride);
  for (Eigen::Index i = 0; i < nodes; ++i) {
    if (model == LawModel::sqrt_fourier) {
      const double theta = angle_per_u * u[i];
      basis(i, 0) = 1.0;
      basis(i, 1) = 1.0 - std::cos(theta);
      basis(i, 2) = std::sin(theta);
    } else {  // powers of u: the quadratic of eq. 149 and the polynomial of eq. 151
      double power = 1.0;
      for (int k = 0; k < stride; ++k, power *= u[i]) basis(i, k) = power;
    }
  }
  // Equal column sizes before the QR: a short arc's 1 − cos θ column is ~θ² small, and without the scaling
  // its coefficient would carry the round-off of the large constant column.
  Eigen::VectorXd scale(stride);
  for (int k = 0; k < stride; ++k) {
    const double size = basis.col(k).cwiseAbs().maxCoeff();
    scale[k] = size > 0.0 ? 1.0 / size : 1.0;
    basis.col(k) *= scale[k];
  }
  // The sqrt models are linear in L², not in L (eqs. 149, 150).
  const Eigen::MatrixXd target = model == LawModel::polynomial ? values : values.cwiseAbs2().eval();
  Eigen::MatrixXd coefficients = basis.colPivHouseholderQr().solve(target);
  for (int k = 0; k < stride; ++k) coefficients.row(k) *= scale[k];
  return coefficients;
}

}  // namespace pkm::interpolation
