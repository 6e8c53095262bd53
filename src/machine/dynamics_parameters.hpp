#pragma once
// What the machine file's `dynamics:` section says about the moving parts' inertia, the struts' elasticity
// and the drives (docs/machine-file.md, docs/dynamics.md). Units inside pkm: mm, kg, s, so forces
// come out in kg·mm/s² = 10⁻³ N and inertias are kg·mm² (the file gives kg·m², as Smirnov 2019 does: × 10⁶).
#include <Eigen/Core>
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

/// A rigid body: mass, centre of mass and the inertia tensor about the centre of mass.
struct BodyInertia {
  double mass_kg = 0.0;
  /// Centre of mass in the body's frame: for the platform and the payload the tool frame (platform axes,
  /// origin at the tool point), mm.
  Eigen::Vector3d com_mm = Eigen::Vector3d::Zero();
  /// About the centre of mass, body axes (the platform's axes), kg·mm²; symmetric positive semi-definite.
  Eigen::Matrix3d inertia_kg_mm2 = Eigen::Matrix3d::Zero();
};

/// One part of a strut, a body on the strut axis, axisymmetric about it (Smirnov, §4.3: the lower part is the
/// cylinder at the base joint A, the upper part the rod at the platform joint B; constant-length struts of
/// glide machines and planar links are a lower part alone).
struct StrutPart {
  double mass_kg = 0.0;
  /// Distance of the centre of mass along the strut axis from the part's own joint: the lower part's from A
  /// towards B, the upper part's from B towards A, mm.
  double com_mm = 0.0;
  /// About the centre of mass, perpendicular to the strut axis, kg·mm². The spin of a strut about its own
  /// axis is not modelled (Smirnov, §4.3: only the perpendicular part of the strut's angular velocity), so
  /// the axial moment of inertia is not needed.
  double transverse_inertia_kg_mm2 = 0.0;
};

/// The friction of a strut's elastic element (Smirnov 2019, §4.2, §4.5): there quadratic in the rate.
enum class StrutDamping { none, viscous, quadratic, coulomb };

/// The drive model (Smirnov 2019, §4.2): ideal (the force is the command), a static characteristic (the force
/// falls linearly with the speed from the command: P = u − k_v·q̇), or a first-order lag τ·Ṗ + P = u.
enum class DriveModel { ideal, static_characteristic, first_order_lag };

struct StrutDynamics {
  StrutPart lower;
  StrutPart upper;
  /// Axial stiffness c_j of the strut's elastic element, N/mm (0: rigid, for the rigid models only).
  double stiffness_N_mm = 0.0;
  StrutDamping damping = StrutDamping::none;
  /// β_j: N·s/mm (viscous), N·s²/mm² (quadratic, the force β·ẋ·|ẋ|), N (Coulomb).
  double damping_coefficient = 0.0;
  /// A moving carriage of a glide machine or rotopod, kg (moves with the base joint; 0 for fixed base
  /// joints).
  double carriage_kg = 0.0;
};

struct DynamicsParameters {
  BodyInertia platform;
  /// The tool or workpiece carried by the platform (tool frame), added to the platform.
  BodyInertia payload;
  int strut_count = 0;
  std::array<StrutDynamics, kMaxActuators> struts{};
  /// Gravitational acceleration in the base frame, mm/s².
  Eigen::Vector3d gravity_mm_s2 = Eigen::Vector3d(0.0, 0.0, -9810.0);
  DriveModel drive = DriveModel::ideal;
  double drive_lag_s = 0.0;              ///< τ of the first-order lag
  double drive_speed_gain_N_s_mm = 0.0;  ///< k_v of the static characteristic
  int line = 0;                          ///< line of `dynamics:` in the machine file (0: not given)
  bool given() const { return line > 0; }
};

}  // namespace pkm
