#pragma once
// What a load does to the tool through a compliance (the outputs per path point): the tool point's
// displacement and the platform's turn δ = C w, the part of the displacement along the tool axis (the surface
// error where the axis is the surface normal: Rusanov's ball-end mill), the struts' tensions c_j g_jᵀ δ, and
// the statistics a program's or a run's points add up to (largest and rms normal error with their lines).
#include <Eigen/Core>

#include "statics/wrench.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

using Vector6 = Eigen::Matrix<double, 6, 1>;

struct ToolDeflection {
  Eigen::Vector3d displacement_mm = Eigen::Vector3d::Zero();  ///< of the tool point, base frame
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();     ///< the platform's small turn, base frame
  double normal_mm = 0.0;  ///< along the tool axis (positive: towards the spindle, away from the work)
  /// Tension positive: what each strut carries against the load. Six struts on a free platform: statics
  /// (Gᵀ T = w, whatever the model); otherwise c_j,eff g_jᵀ δ, or NaN where an elastic frame moves the
  /// struts' base ends (their tensions are the frame model's own deflection(), frame_model.hpp).
  ActuatorVector strut_force_N;
};

/// δ = C w and what follows from it, `tool_axis` the unit tool axis (base frame) at the pose.
ToolDeflection deflect(const ToolCompliance& compliance, const statics::Wrench& load,
                       const Eigen::Vector3d& tool_axis);

/// The largest and rms normal error over points (cutting points for the rms), with their program lines.
struct DeflectionStatistics {
  double max_normal_mm = 0.0;  ///< largest |normal deflection|
  int max_normal_line = 0;
  long max_normal_index = -1;      ///< the point's (or tick's) index
  double rms_normal_mm = 0.0;      ///< over the cutting points, after finish()
  double max_deflection_mm = 0.0;  ///< largest |displacement|
  int max_deflection_line = 0;
  double max_strut_force_N = 0.0;  ///< largest |tension|
  int max_strut_force_strut = 0;   ///< 1-based
  int max_strut_force_line = 0;
  long points = 0;
  long cutting_points = 0;

  void add(long index, int line, bool cutting, const ToolDeflection& deflection);
  void finish();

 private:
  double normal_square_sum_ = 0.0;
};

}  // namespace pkm::stiffness
