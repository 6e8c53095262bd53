#pragma once
// One piece of the analytic strut laws L_j(s) (Smirnov 2019): a model, its coefficients for every actuator
// and the local variable it is written in. Every fitted model is written in the normalised variable
//   u = (s − s_mid)·u_per_s ∈ [−1, 1]
// of its piece, so that the coefficients stay of one size whatever the piece's place and length on the path
// (conditioning of the fit and round-off of the evaluation). Per actuator, with c = its coefficients:
//   sqrt_quadratic (line, eq. 149):  L² = c0 + c1·u + c2·u²
//   sqrt_fourier   (arc, eqs. 148/150): L² = c0 + c1·(1 − cos θ) + c2·sin θ,  θ = angle_per_u·u
//     (eq. 148's a0 + a1 cos θ + b1 sin θ with the angle origin at the piece's middle; 1 − cos θ instead of
//     cos θ keeps the columns of a short arc's fit apart: they tend to 1, θ²/2 and θ, not to 1, 1 and θ)
//   polynomial     (anything else, eq. 151): L = c0 + c1·u + … + c_d·u^d  (d = stride − 1, Horner)
// Evaluation costs one sqrt per actuator for the sqrt models, plus one sin and one cos for the whole piece.
#include <cmath>
#include <string_view>

namespace pkm::interpolation {

enum class LawModel { exact, sqrt_quadratic, sqrt_fourier, polynomial };
std::string_view to_string(LawModel model);

struct LawPiece {
  double s_start = 0.0;  ///< path parameter where the piece starts (it ends where the next one starts)
  double s_end = 0.0;
  double s_mid = 0.0;
  double u_per_s = 0.0;      ///< 2/length (0 for a piece of zero length: u = 0)
  double angle_per_u = 0.0;  ///< sqrt_fourier: the arc angle θ (rad) per unit of u, from the piece's middle
  LawModel model = LawModel::exact;
  int segment = 0;         ///< path segment the piece lies on
  int line = 0;            ///< source line of that segment
  int offset = 0;          ///< first coefficient of the piece in the coefficient table
  int stride = 0;          ///< coefficients per actuator (0 for exact pieces)
  double fit_error = 0.0;  ///< largest measured |fitted − IK| at the piece's check points

  double u(double s) const noexcept { return (s - s_mid) * u_per_s; }
};

/// The fitted values of all `actuators` laws of `piece` at s; `coefficients` points at the piece's table
/// (its `offset`), actuator j's coefficients at j·stride. Not for exact pieces. No allocation.
inline void evaluate_fitted_piece(const LawPiece& piece, const double* coefficients, int actuators, double s,
                                  double* values) noexcept {
  const double u = piece.u(s);
  switch (piece.model) {
    case LawModel::sqrt_quadratic:
      for (int j = 0; j < actuators; ++j) {
        const double* c = coefficients + 3 * j;
        values[j] = std::sqrt(std::fmax(0.0, c[0] + u * (c[1] + u * c[2])));
      }
      return;
    case LawModel::sqrt_fourier: {
      const double theta = piece.angle_per_u * u;
      const double versine = 1.0 - std::cos(theta);
      const double sine = std::sin(theta);
      for (int j = 0; j < actuators; ++j) {
        const double* c = coefficients + 3 * j;
        values[j] = std::sqrt(std::fmax(0.0, c[0] + c[1] * versine + c[2] * sine));
      }
      return;
    }
    case LawModel::polynomial:
      for (int j = 0; j < actuators; ++j) {
        const double* c = coefficients + piece.stride * j;
        double value = c[piece.stride - 1];
        for (int k = piece.stride - 2; k >= 0; --k) value = value * u + c[k];
        values[j] = value;
      }
      return;
    case LawModel::exact:
      return;
  }
}

}  // namespace pkm::interpolation
