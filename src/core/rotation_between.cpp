#include "core/rotation_between.hpp"

#include <cmath>

namespace pkm {

Eigen::Matrix3d rodrigues_matrix(const Eigen::Vector3d& v, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad), t = 1.0 - c;
  Eigen::Matrix3d r;
  r(0, 0) = c + v.x() * v.x() * t;
  r(0, 1) = v.x() * v.y() * t - v.z() * s;  // the corrected entry (1,2) (printed: v_z² sin φ)
  r(0, 2) = v.x() * v.z() * t + v.y() * s;
  r(1, 0) = v.y() * v.x() * t + v.z() * s;
  r(1, 1) = c + v.y() * v.y() * t;
  r(1, 2) = v.y() * v.z() * t - v.x() * s;
  r(2, 0) = v.z() * v.x() * t - v.y() * s;
  r(2, 1) = v.z() * v.y() * t + v.x() * s;
  r(2, 2) = c + v.z() * v.z() * t;
  return r;
}

Eigen::Matrix3d rotation_between(const Eigen::Vector3d& n_old, const Eigen::Vector3d& n_new) {
  const Eigen::Vector3d cross = n_old.cross(n_new);
  const double sine = cross.norm();
  const double cosine = n_old.dot(n_new);
  // The angle from both its sine and cosine: accurate near 0 and near π, where acos alone is not.
  const double angle = std::atan2(sine, cosine);
  if (sine > 1e-12) return rodrigues_matrix(cross / sine, angle);
  if (cosine > 0.0) return Eigen::Matrix3d::Identity();
  // Opposite: any axis square to n_old turns it onto −n_old by a half turn; the cross product with the
  // coordinate axis n_old has the least of is well away from zero.
  Eigen::Index closest = 0;
  n_old.cwiseAbs().minCoeff(&closest);
  const Eigen::Vector3d axis = n_old.cross(Eigen::Vector3d::Unit(closest)).normalized();
  return rodrigues_matrix(axis, angle);
}

}  // namespace pkm
