#include "stiffness/tool_deflection.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace pkm::stiffness {

ToolDeflection deflect(const ToolCompliance& compliance, const statics::Wrench& load,
                       const Eigen::Vector3d& tool_axis) {
  Vector6 wrench;
  wrench << load.force_N, load.moment_Nmm;
  const Vector6 twist = compliance.compliance * wrench;
  ToolDeflection out;
  out.displacement_mm = twist.head<3>();
  out.rotation_rad = twist.tail<3>();
  out.normal_mm = out.displacement_mm.dot(tool_axis);
  const int struts = static_cast<int>(compliance.strut_lines.rows());
  if (struts == 6 && compliance.dof == 6) {
    // Six struts holding a free platform are statically determinate: Gᵀ T = w whatever gives way (struts,
    // joints, frame).
    const Eigen::Matrix<double, 6, 6> lines = compliance.strut_lines;
    out.strut_force_N = lines.transpose().partialPivLu().solve(wrench);
  } else if (compliance.tensions_from_stretch) {
    // Tension = stiffness × stretch along the strut's line (strut_compliance.hpp).
    out.strut_force_N = compliance.strut_stiffness_N_mm.cwiseProduct(compliance.strut_lines * twist);
  } else {
    out.strut_force_N.setConstant(struts, std::numeric_limits<double>::quiet_NaN());  // not known here
  }
  return out;
}

void DeflectionStatistics::add(long index, int line, bool cutting, const ToolDeflection& deflection) {
  ++points;
  if (cutting) {
    ++cutting_points;
    normal_square_sum_ += deflection.normal_mm * deflection.normal_mm;
  }
  if (std::abs(deflection.normal_mm) > max_normal_mm) {
    max_normal_mm = std::abs(deflection.normal_mm);
    max_normal_line = line;
    max_normal_index = index;
  }
  if (deflection.displacement_mm.norm() > max_deflection_mm) {
    max_deflection_mm = deflection.displacement_mm.norm();
    max_deflection_line = line;
  }
  for (int j = 0; j < deflection.strut_force_N.size(); ++j) {
    if (std::abs(deflection.strut_force_N[j]) > max_strut_force_N) {
      max_strut_force_N = std::abs(deflection.strut_force_N[j]);
      max_strut_force_strut = j + 1;
      max_strut_force_line = line;
    }
  }
}

void DeflectionStatistics::finish() {
  rms_normal_mm = cutting_points > 0 ? std::sqrt(normal_square_sum_ / cutting_points) : 0.0;
}

}  // namespace pkm::stiffness
