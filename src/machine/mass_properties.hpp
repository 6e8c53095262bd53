#pragma once
// What the machine file's `masses:` section says about the moving parts' weight (docs/machine-file.md).
// Smirnov 2019's chapter-3 statics include the platform's weight as an external load but give no masses
// (chapter 4 says so); chapter 4 uses a 60 kg platform and 15 + 10 kg struts.
#include <Eigen/Core>

namespace pkm {

/// Masses and gravity; all zero masses (the default) mean no gravity load. `*_line` is the line of the key in
/// the machine file, for messages (0 = not given).
struct MassProperties {
  double platform_kg = 0.0;
  /// The platform's centre of mass in the tool frame (platform axes, origin at the tool point), mm.
  Eigen::Vector3d platform_com_mm = Eigen::Vector3d::Zero();
  /// Each strut's (leg's) moving part; statics carries half its weight at the platform-side joint and half at
  /// the base (an approximation: the mass is taken as centred between the joints).
  double strut_kg = 0.0;
  /// Gravitational acceleration in the base frame, mm/s² (Smirnov 2019 never says which way +z points).
  Eigen::Vector3d gravity_mm_s2 = Eigen::Vector3d(0.0, 0.0, -9810.0);
  int line = 0;  ///< line of `masses:` (0 = section not given)
  int platform_kg_line = 0;
  int platform_com_line = 0;
  int strut_kg_line = 0;
  int gravity_line = 0;

  bool has_mass() const { return platform_kg > 0.0 || strut_kg > 0.0; }
};

}  // namespace pkm
