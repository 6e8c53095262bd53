#include "kinematics/coordinate_jacobian.hpp"

namespace pkm {

JacobianMatrix coordinate_jacobian(const JacobianMatrix& twist_jacobian, AngleConvention convention,
                                   const Eigen::Vector3d& angles_rad, const AxisMask& mask) {
  const int n = static_cast<int>(twist_jacobian.rows());
  JacobianMatrix full(n, 6);
  full.leftCols<3>() = twist_jacobian.leftCols<3>();
  full.rightCols<3>() = twist_jacobian.rightCols<3>() * angular_velocity_matrix(convention, angles_rad);
  JacobianMatrix out(n, mask.count());
  int column = 0;
  for (int i = 0; i < 6; ++i) {
    if (mask.controlled[i]) out.col(column++) = full.col(i);
  }
  return out;
}

}  // namespace pkm
