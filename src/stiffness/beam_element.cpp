#include "stiffness/beam_element.hpp"

namespace pkm::stiffness {

// Twist and wrench order: (x, y, z, φ_x, φ_y, φ_z), (Q_x, Q_y, Q_z, M_x, M_y, M_z).
Matrix6 cantilever_compliance(const BeamSection& s, double length_mm) {
  const double l = length_mm;
  const double ejx = s.modulus_N_mm2 * s.second_moment_x_mm4;
  const double ejy = s.modulus_N_mm2 * s.second_moment_y_mm4;
  Matrix6 c = Matrix6::Zero();
  // Bending in the x-z plane about y: u_x and φ_y from Q_x and M_y.
  c(0, 0) = l * l * l / (3.0 * ejy);
  c(0, 4) = c(4, 0) = l * l / (2.0 * ejy);
  c(4, 4) = l / ejy;
  // Bending in the y-z plane about x: u_y and φ_x from Q_y and M_x; the coupling turns the other way.
  c(1, 1) = l * l * l / (3.0 * ejx);
  c(1, 3) = c(3, 1) = -l * l / (2.0 * ejx);
  c(3, 3) = l / ejx;
  c(2, 2) = l / (s.modulus_N_mm2 * s.area_mm2);
  c(5, 5) = l / (s.shear_modulus_N_mm2 * s.torsion_constant_mm4);
  return c;
}

Matrix6 cantilever_stiffness(const BeamSection& s, double length_mm) {
  const double l = length_mm;
  const double ejx = s.modulus_N_mm2 * s.second_moment_x_mm4;
  const double ejy = s.modulus_N_mm2 * s.second_moment_y_mm4;
  Matrix6 k = Matrix6::Zero();
  k(0, 0) = 12.0 * ejy / (l * l * l);
  k(0, 4) = k(4, 0) = -6.0 * ejy / (l * l);
  k(4, 4) = 4.0 * ejy / l;
  k(1, 1) = 12.0 * ejx / (l * l * l);
  k(1, 3) = k(3, 1) = 6.0 * ejx / (l * l);
  k(3, 3) = 4.0 * ejx / l;
  k(2, 2) = s.modulus_N_mm2 * s.area_mm2 / l;
  k(5, 5) = s.shear_modulus_N_mm2 * s.torsion_constant_mm4 / l;
  return k;
}

Matrix6 rigid_transfer(const Eigen::Vector3d& r) {
  Matrix6 h = Matrix6::Identity();
  // u + φ × r = u − [r]× φ.
  h.block<3, 3>(0, 3) << 0.0, r.z(), -r.y(), -r.z(), 0.0, r.x(), r.y(), -r.x(), 0.0;
  return h;
}

Matrix12 beam_stiffness_local(const BeamSection& section, double length_mm) {
  const Matrix6 k11 = cantilever_stiffness(section, length_mm);
  const Matrix6 h = rigid_transfer(Eigen::Vector3d(0.0, 0.0, length_mm));
  Matrix12 k;
  k.block<6, 6>(6, 6) = k11;
  k.block<6, 6>(6, 0) = -k11 * h;
  k.block<6, 6>(0, 6) = k.block<6, 6>(6, 0).transpose();
  k.block<6, 6>(0, 0) = h.transpose() * k11 * h;
  return k;
}

Eigen::Matrix3d beam_axes(const Eigen::Vector3d& axis, const Eigen::Vector3d& section_x) {
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d x = (section_x - section_x.dot(z) * z).normalized();
  Eigen::Matrix3d gamma;
  gamma.row(0) = x.transpose();
  gamma.row(1) = z.cross(x).transpose();
  gamma.row(2) = z.transpose();
  return gamma;
}

Matrix12 beam_stiffness_global(const BeamSection& section, const Eigen::Vector3d& from_mm,
                               const Eigen::Vector3d& to_mm, const Eigen::Vector3d& section_x) {
  const Eigen::Vector3d d = to_mm - from_mm;
  const Eigen::Matrix3d gamma = beam_axes(d, section_x);
  Matrix12 big_gamma = Matrix12::Zero();
  for (int b = 0; b < 4; ++b) big_gamma.block<3, 3>(3 * b, 3 * b) = gamma;
  return big_gamma.transpose() * beam_stiffness_local(section, d.norm()) * big_gamma;
}

}  // namespace pkm::stiffness
