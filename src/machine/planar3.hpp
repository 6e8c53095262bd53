#pragma once
// Planar 3-DOF platform, 3-RPR (Smirnov 2019, §2.1.2, Fig. 23 and §3.2–3.3).
//   B_j = R(φ)·b'_j + C,   L_j = |B_j − A_j|                      (eq. 8 = eq. 79)
//   ∂L_j/∂(x_C, y_C, φ) = (u_jᵀ, (R b'_j) × u_j),  u_j = (B_j − A_j)/L_j   (eq. 80)
// A_j: base joints in the base frame; b'_j: platform joints in the tool frame (platform frame shifted to the
// tool point, so C is the tool point). The pose is PoseVector (x, y, 0, 0, 0, φ) in the abc convention:
// R = Rz(φ). The assembly mode is the sign of det J (§3.3: a mechanism cannot pass a singular position, so
// the sign of the Jacobian determinant separates the modes it can reach from a start pose).
#include <Eigen/Core>
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct Planar3Geometry {
  std::array<Eigen::Vector2d, 3> base_joints_mm;      ///< A_j in the base frame
  std::array<Eigen::Vector2d, 3> platform_joints_mm;  ///< b'_j in the tool frame
};

/// Planar coordinates (x_C mm, y_C mm, φ rad) of a pose; φ from the rotation's in-plane part.
Eigen::Vector3d planar_coordinates(const Pose& pose);
/// The pose (x, y, 0) with R = Rz(φ) for planar coordinates (x mm, y mm, φ rad).
Pose pose_from_planar(const Eigen::Vector3d& xyphi);

class Planar3 final : public Mechanism {
 public:
  /// `home`: planar coordinates (x mm, y mm, φ rad); must not be singular (checked by the machine-file
  /// entry).
  Planar3(const Planar3Geometry& geometry, const Eigen::Vector3d& home);

  MechanismType type() const override { return MechanismType::planar3; }
  int actuator_count() const override { return 3; }
  AngleConvention convention() const override { return AngleConvention::abc; }
  AxisMask controlled_axes() const override { return {{true, true, false, false, false, true}}; }

  /// Keeps x, y and the in-plane angle; z = 0 and R = Rz(φ).
  Result<Pose> complete_pose(const Pose& pose) const override;
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Damped Newton in (x, y, φ) from the guess. With options.require_same_branch, a solution whose sign of
  /// det J differs from the guess's is a wrong_branch error. branch: 0 = sign of det J as at home, 1 = the
  /// other sign. When Newton fails and forward_all finds no solution at all, the error is unreachable.
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode (at most 6), nearest to home first (planar3_assembly_modes.cpp).
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  /// 3 × 3, columns (x, y, φ): eq. (80).
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// strut_lengths(); false when a strut would have zero length (as inverse()).
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  /// Eq. (80) in twist form: rows (u_x, u_y, 0, 0, 0, (R b'_j) × u_j); the platform moves in the plane, so
  /// only the v_x, v_y and ω_z columns meet twists it can make.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// Base pins A_j and platform pins R(φ) b'_j + C, in z = 0.
  int strut_ends(const Pose& pose, StrutJointPoints& out) const override;
  bool is_planar() const override { return true; }
  double platform_size_mm() const override { return platform_radius_mm_; }
  /// Base, platform, three two-part struts; 9 one-DOF pairs.
  MechanismStructure structure() const override { return {"3-RPR (planar)", true, 8, {9, 0, 0, 0, 0}, 0}; }
  /// base_joints A1..A3 (base frame) and platform_joints_from_tool B1..B3 (tool frame), 3 × [x, y] mm each.
  std::vector<GeometryGroup> geometry_parameters() const override;
  /// Keeps the home (x, y, φ); the sign of det J there stays the assembly mode.
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  /// Hot path: strut lengths at planar coordinates, no checks, no allocation.
  void strut_lengths(const Eigen::Vector3d& xyphi, double* lengths_mm) const noexcept;
  /// Eq. (80) at planar coordinates; rows with a zero strut length are left zero.
  Eigen::Matrix3d planar_jacobian(const Eigen::Vector3d& xyphi) const noexcept;
  /// det J with the φ column divided by the platform radius: dimensionless, |value| ≤ 2^(3/2), 0 = singular.
  double normalized_determinant(const Eigen::Vector3d& xyphi) const noexcept;

  /// Newton's method from `start` without the branch rule (shared by forward and forward_all).
  Result<FkSolution> solve_from(const ActuatorVector& actuators, const Eigen::Vector3d& start,
                                const FkOptions& options) const;

  const Planar3Geometry& geometry() const { return geometry_; }
  /// Radius of the platform joints about the tool point (mm); scales φ to a length in conditioning checks.
  double platform_radius_mm() const { return platform_radius_mm_; }
  /// Sign of det J: +1, −1, or 0 when |normalized_determinant| is below `singular_below`.
  int determinant_sign(const Eigen::Vector3d& xyphi, double singular_below = 0.0) const noexcept;

 private:
  int branch_of(const Eigen::Vector3d& xyphi) const noexcept;

  Planar3Geometry geometry_;
  double platform_radius_mm_ = 1.0;
  int home_sign_ = 1;
};

}  // namespace pkm
