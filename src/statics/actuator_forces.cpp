// The generic statics solve for every mechanism: generalised forces in the controlled coordinates, then the
// transposed Jacobian (Smirnov 2019, (73)/(91) written as J_cᵀ P = −Q).
#include "statics/actuator_forces.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "statics/coordinate_twist.hpp"

namespace pkm::statics {

Result<ActuatorVector> actuator_forces(const Mechanism& mechanism, const Pose& pose, const Wrench& load) {
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  // The actuators must exist at this pose before their forces mean anything.
  if (auto reach = mechanism.inverse(*completed); !reach) return reach.error();
  auto jacobian = mechanism.jacobian(*completed);
  if (!jacobian) return jacobian.error();
  const int n = static_cast<int>(jacobian->rows());
  const int m = static_cast<int>(jacobian->cols());
  if (n != m) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("statics: {} actuators for {} controlled coordinates; the forces are not "
                                  "determined by statics alone",
                                  n, m));
  }
  auto basis = controlled_twist_basis(mechanism, *completed);
  if (!basis) return basis.error();

  Eigen::Matrix<double, 6, 1> w;
  w << load.force_N, load.moment_Nmm;
  // Virtual work of the load per unit rate of each controlled coordinate.
  const ActuatorVector q = basis->transpose() * w;

  // Columns in mm/mm and mm/rad: equilibrate them (J = J̃ D) so that the singularity test does not depend on
  // units; J̃ᵀ P = −D⁻¹ Q.
  JacobianMatrix scaled = *jacobian;
  ActuatorVector column_norm(m);
  for (int c = 0; c < m; ++c) {
    column_norm[c] = scaled.col(c).norm();
    if (!(column_norm[c] > 0.0)) {
      return make_error(ErrorCode::singular,
                        fmt::format("statics: the Jacobian is singular at this pose (no actuator moves {})",
                                    controlled_coordinate_names(mechanism)[c]));
    }
    scaled.col(c) /= column_norm[c];
  }
  const Eigen::FullPivLU<JacobianMatrix> lu(scaled.transpose());
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  const double ratio = pivots.maxCoeff() > 0.0 ? pivots.minCoeff() / pivots.maxCoeff() : 0.0;
  if (!(ratio > kSingularPivotRatio)) {
    return make_error(
        ErrorCode::singular,
        fmt::format("statics: the Jacobian is singular at this pose (pivot ratio {:.3g} <= {:.0e}); "
                    "the actuators cannot hold the load",
                    ratio, kSingularPivotRatio));
  }
  const ActuatorVector rhs = -q.cwiseQuotient(column_norm);
  ActuatorVector forces = lu.solve(rhs);
  return forces;
}

}  // namespace pkm::statics
