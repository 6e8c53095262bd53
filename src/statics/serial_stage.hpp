#pragma once
// Smirnov 2019's motivating example (§3.1, (66)–(71), Figs. 57–61): a serial 2-axis stage with
// drives along X and Y carrying a translating platform. An external force, split into P_τ along the step dL
// (direction φ from X) and P_n perpendicular to it, is held by the two drives; the useful energy counts every
// drive's work as consumed (no regeneration) and so exceeds the required work except when one drive does all
// of it.
namespace pkm::statics {

/// Drive forces of (66): P_X = P_τ cos φ − P_n sin φ, P_Y = P_τ sin φ + P_n cos φ.
struct SerialStageDriveForces {
  double x_N = 0.0;
  double y_N = 0.0;
};
SerialStageDriveForces serial_stage_drive_forces(double tangential_N, double normal_N, double feed_angle_rad);

/// Energy of one step of length dL at feed angle φ (N·mm = mJ):
///   useful   (68): |P_X dL cos φ| + |P_Y dL sin φ|,
///   friction (§3.1, Fig. 61): |f P_X dL sin φ| + |f (P_Y + f P_X) dL cos φ| — the Y drive rides on the X
///   drive,
///            so the X guide carries the Y drive's friction as well,
///   required (69): |P_τ dL|, the work of the external force.
struct SerialStageEnergy {
  double useful_Nmm = 0.0;
  double friction_Nmm = 0.0;
  double required_Nmm = 0.0;
  double total_Nmm() const { return useful_Nmm + friction_Nmm; }  ///< the "total" of the §3.1 table
};
SerialStageEnergy serial_stage_step_energy(double tangential_N, double normal_N, double feed_angle_rad,
                                           double step_mm, double friction_coefficient);

}  // namespace pkm::statics
