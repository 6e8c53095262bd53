#include "statics/serial_stage.hpp"

#include <cmath>

namespace pkm::statics {

SerialStageDriveForces serial_stage_drive_forces(double tangential_N, double normal_N,
                                                 double feed_angle_rad) {
  const double c = std::cos(feed_angle_rad);
  const double s = std::sin(feed_angle_rad);
  return {tangential_N * c - normal_N * s, tangential_N * s + normal_N * c};  // (66)
}

SerialStageEnergy serial_stage_step_energy(double tangential_N, double normal_N, double feed_angle_rad,
                                           double step_mm, double friction_coefficient) {
  const SerialStageDriveForces p = serial_stage_drive_forces(tangential_N, normal_N, feed_angle_rad);
  const double dx = step_mm * std::cos(feed_angle_rad);
  const double dy = step_mm * std::sin(feed_angle_rad);
  const double f = friction_coefficient;
  SerialStageEnergy e;
  // (68): a braking drive still consumes |dA| (no regeneration, Smirnov 2019, §3.1).
  e.useful_Nmm = std::abs(p.x_N * dx) + std::abs(p.y_N * dy);
  // Friction (Fig. 61): the Y drive's transverse load is P_X; the X drive's is P_Y plus the Y drive's
  // friction.
  e.friction_Nmm = std::abs(f * p.x_N * dy) + std::abs(f * (p.y_N + f * p.x_N) * dx);
  // (67), (69): only P_τ does work over the step.
  e.required_Nmm = std::abs(tangential_N * step_mm);
  return e;
}

}  // namespace pkm::statics
