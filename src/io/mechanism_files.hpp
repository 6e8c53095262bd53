#pragma once
// One machine-file entry per mechanism; each is defined next to its mechanism in `<mechanism>_file.cpp`.
#include "io/machine_file.hpp"
#include "machine/hexapod.hpp"

namespace pkm {

MechanismFileEntry planar2_file_entry();
MechanismFileEntry planar3_file_entry();
MechanismFileEntry hexapod_file_entry();
MechanismFileEntry hexapod_refined_file_entry();
MechanismFileEntry tripod_file_entry();
MechanismFileEntry tricept_file_entry();
MechanismFileEntry glide_file_entry();
MechanismFileEntry rotopod_file_entry();

/// The keys shared by the ideal and refined hexapods: base_joints, platform_joints (shifted by `tool`), and
/// home.
struct HexapodFileGeometry {
  HexapodGeometry geometry;
  Pose home;
};
Result<HexapodFileGeometry> read_hexapod_geometry(const MechanismSpec& spec);

/// Default home for mechanisms whose platform hangs above a base: x = y = 0, angles 0, and the height at
/// which the mean actuator length is mid-range (or 1.2 × the mean base radius without limits). Returns z of
/// the tool point.
double default_home_height_mm(const std::vector<Eigen::Vector3d>& base_joints_mm,
                              const std::vector<Eigen::Vector3d>& platform_joints_tool_mm,
                              const ActuatorLimits& limits);

}  // namespace pkm
