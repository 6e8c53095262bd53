#include "statics/wrench.hpp"

#include <Eigen/Geometry>

namespace pkm::statics {

Wrench shift_wrench(const Wrench& wrench, const Eigen::Vector3d& from_point_mm,
                    const Eigen::Vector3d& to_point_mm) {
  // Each force f at r contributes (r − to) × f = (r − from) × f + (from − to) × f.
  return {wrench.force_N, wrench.moment_Nmm + (from_point_mm - to_point_mm).cross(wrench.force_N)};
}

Wrench operator+(const Wrench& a, const Wrench& b) {
  return {a.force_N + b.force_N, a.moment_Nmm + b.moment_Nmm};
}

}  // namespace pkm::statics
