#include "core/rotation_angle.hpp"

#include <cmath>

#include "core/units.hpp"

namespace pkm {

double RotationAngle::degrees() const {
  return deg_from_rad(std::atan2(sin, cos));
}

RotationAngle RotationAngle::of_degrees(double angle_deg) {
  return {std::sin(rad_from_deg(angle_deg)), std::cos(rad_from_deg(angle_deg))};
}

RotationAngle rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  auto d = [&](int i, int k) { return a.row(i).dot(b.row(k)); };  // D(i, k)
  const Eigen::Vector3d skew(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return {0.5 * skew.norm(), 0.5 * (d(0, 0) + d(1, 1) + d(2, 2) - 1.0)};
}

}  // namespace pkm
