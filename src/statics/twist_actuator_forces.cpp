// Statics on the hot path for six-actuator, six-coordinate mechanisms (Smirnov (91) about the tool point):
// fixed-size, no allocation. Any mechanism with a square twist Jacobian takes it; the hexapod was its first.
#include <cmath>

#include "kinematics/fixed_lu.hpp"
#include "statics/actuator_forces.hpp"

namespace pkm::statics {

bool twist_actuator_forces(const Mechanism& mechanism, const Pose& pose, const Wrench& load,
                           double* forces_N) noexcept {
  // Row j of J_t is the line of actuator j about the tool point: for a strut (u_j, b_j × u_j), its Plücker
  // line, i.e. column j of (91)'s a_ij with the moment taken about the tool point instead of O.
  JacobianMatrix twist;
  if (!mechanism.twist_jacobian(pose, twist) || twist.rows() != 6 || twist.cols() != 6) return false;
  const Eigen::Matrix<double, 6, 6> j = twist;
  // Equilibrate the columns (unit-free singularity test, as in actuator_forces): J = J̃ D, J̃ᵀ P = −D⁻¹ w.
  Eigen::Matrix<double, 6, 1> norm;
  for (int c = 0; c < 6; ++c) {
    norm[c] = j.col(c).norm();
    if (!(norm[c] > 0.0)) return false;
  }
  Eigen::Matrix<double, 6, 1> rhs;
  rhs << load.force_N, load.moment_Nmm;
  rhs = -rhs.cwiseQuotient(norm);
  FixedLu<6> lu;
  lu.compute((j * norm.cwiseInverse().asDiagonal()).transpose());
  if (!(lu.pivot_ratio() > kSingularPivotRatio)) return false;
  const Eigen::Matrix<double, 6, 1> p = lu.solve(rhs);
  for (int k = 0; k < 6; ++k) {
    if (!std::isfinite(p[k])) return false;
    forces_N[k] = p[k];
  }
  return true;
}

}  // namespace pkm::statics
