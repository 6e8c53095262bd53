#pragma once
// Hexapod 6-UPS with real (non-ideal) cardan joints at the base: Smirnov 2019, §2.2.5 (eqs. 27–28).
//
// A real cardan joint has two revolute axes that are skew, not quite perpendicular, and whose "centre" is not
// on the strut axis. In a calibratable form (each joint matrix = a constant calibrated axis × a
// rotation about it by the joint angle), the platform-joint centre of leg j is, in the base frame,
//
//   B_j = R0_j + R1_j + Rot(a1_j, g1)·( R2_j + Rot(a2_j, g2)·( R3_j + L_j·u_j ) )          (eq. 27 + R0, eq.
//   28)
//
//   R0  ideal joint centre A_j (`base_joints`)              a1  first revolute axis, base frame (nominal y)
//   R1  point on the first axis, from A_j (eq. 28 R')        a2  second axis, yoke frame (nominal x)
//   R2  point on the second axis, from that (eq. 28 R'')     u   strut direction, second-joint frame (nominal
//   z) R3  point A* of the strut axis, from that (eq. 28 R*)    g1, g2  joint angles (unknown), L = |B − A*|
//   strut length
//
// Rot(a, g) turns about the unit axis a by g. The yoke frame and the second-joint frame coincide with the
// base frame's orientation when g1 = g2 = 0, so every constant is given in base-frame directions of the
// zero-angle joint. The constant alignment matrices of eq. 28's A' and A'' are absorbed into a1, a2, u (a
// rotation about a calibrated axis is the alignment·Rot·alignmentᵀ of eq. 28, and the trailing alignmentᵀ
// is a constant change of frame for R2, R3, u). With zero offsets, |B − A| = L for any unit axes, so the
// defaults give exactly the ideal hexapod (eq. 20/22).
//
// IK: per leg, 3 equations in (g1, g2, L): Newton from the ideal-joint solution (pkm's own). FK:
// Newton on the pose with ∂L/∂B from implicit differentiation of the leg map
// (kinematics/platform_newton.hpp); the 12 joint angles are eliminated leg by leg, so the 18-unknown system
// of eq. 28 becomes the usual 6-unknown one.
#include <array>

#include "machine/base_plane.hpp"
#include "machine/hexapod.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

/// Calibration constants of one real cardan joint (all directions are normalised by the constructor).
struct CardanJoint {
  Eigen::Vector3d axis1 = Eigen::Vector3d::UnitY();           ///< a1, base frame
  Eigen::Vector3d offset1_mm = Eigen::Vector3d::Zero();       ///< R1 = eq. 28's R', base frame
  Eigen::Vector3d axis2 = Eigen::Vector3d::UnitX();           ///< a2, yoke frame
  Eigen::Vector3d offset2_mm = Eigen::Vector3d::Zero();       ///< R2 = eq. 28's R'', yoke frame
  Eigen::Vector3d strut_offset_mm = Eigen::Vector3d::Zero();  ///< R3 = eq. 28's R*, second-joint frame
  Eigen::Vector3d strut_axis = Eigen::Vector3d::UnitZ();      ///< u, second-joint frame
};

/// The leg's unknowns of eq. 28 at one pose.
struct CardanLegState {
  double length_mm = 0.0;
  double angle1_rad = 0.0;  ///< g1, about a1
  double angle2_rad = 0.0;  ///< g2, about a2
};

enum class CardanLegStatus {
  ok,
  folded,         ///< the solution needs a joint angle beyond ±90° or a non-positive length
  singular,       ///< the leg map is singular (gimbal lock: the strut lies along the first axis)
  not_converged,  ///< the per-leg Newton did not converge
};

/// Solves eq. 28 for one leg: the (L, g1, g2) that put the strut end on `platform_joint_mm`. Starts from the
/// ideal joint (Paden–Kahan two-axis solution, offsets ignored) and polishes by Newton. `dL_dB`, if given,
/// receives ∂L/∂B.
CardanLegStatus solve_cardan_leg(const CardanJoint& joint, const Eigen::Vector3d& base_joint_mm,
                                 const Eigen::Vector3d& platform_joint_mm, CardanLegState& state,
                                 Eigen::Vector3d* dL_dB = nullptr);

/// The strut end B of eq. 28 for given joint angles and length.
Eigen::Vector3d cardan_strut_end(const CardanJoint& joint, const Eigen::Vector3d& base_joint_mm,
                                 const CardanLegState& state);

class HexapodRefined final : public Mechanism {
 public:
  HexapodRefined(const HexapodGeometry& geometry, const std::array<CardanJoint, 6>& joints,
                 AngleConvention convention, const Pose& home);

  MechanismType type() const override { return MechanismType::hexapod_refined; }
  int actuator_count() const override { return 6; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override { return AxisMask::all(); }

  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode: the ideal hexapod's modes (any layout), each polished with the real joints.
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// The ideal joint centres, as Hexapod (the calibrated offsets, a fraction of a mm, move a joint's angle
  /// by less than offset/length: far below any swing limit's resolution).
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;

  /// Strut lengths and cardan angles of every leg at a pose.
  Result<std::array<CardanLegState, 6>> leg_states(const Pose& pose) const;
  /// Twist Jacobian (columns v, ω about the tool point): rows ∂L_j/∂B_j and (R·b'_j) × ∂L_j/∂B_j.
  Result<Eigen::Matrix<double, 6, 6>> twist_jacobian(const Pose& pose) const;
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// The cardan offsets are a fraction of a mm: the lengths stay close to |C + R·b' − A|, and the law fit's
  /// error check rejects a closed model where they do not.
  bool has_distance_actuators() const override { return true; }
  /// As the hexapod: 6 × (U, P or H, S); base + platform + 12 strut parts.
  MechanismStructure structure() const override { return {"6-UPS", false, 14, {6, 6, 6, 0, 0}, 0}; }
  /// The hexapod's base_joints A1..A6 and platform_joints_from_tool B1..B6, then the joints' offsets
  /// cardan_offset1 (R'), cardan_offset2 (R'') and cardan_strut_offset (R*), 6 × 3 mm each. The axes stay
  /// fixed: with them known, at most 60 of these and the drive offsets are identifiable (the calibration's
  /// SVD finds which).
  std::vector<GeometryGroup> geometry_parameters() const override;
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  const HexapodGeometry& geometry() const { return geometry_; }
  const std::array<CardanJoint, 6>& joints() const { return joints_; }
  /// The same machine with ideal joints (used for assembly-mode enumeration and as a reference).
  const Hexapod& ideal() const { return ideal_; }

  // Leg interface for solve_platform_fk.
  int leg_count() const { return 6; }
  const Eigen::Vector3d& platform_joint(int j) const { return geometry_.platform_joints_mm[j]; }
  bool leg_value(int j, const Eigen::Vector3d& joint, double& q, Eigen::Vector3d& g) const {
    CardanLegState state;
    if (solve_cardan_leg(joints_[j], geometry_.base_joints_mm[j], joint, state, &g) != CardanLegStatus::ok) {
      return false;
    }
    q = state.length_mm;
    return true;
  }

 private:
  /// Assembly-mode signature as for the ideal hexapod: sign of det J and side of the base plane; −1 if
  /// undefined.
  int assembly_mode(const Pose& pose) const;

  HexapodGeometry geometry_;
  std::array<CardanJoint, 6> joints_;
  AngleConvention convention_;
  Hexapod ideal_;
  BasePlane base_plane_;
  int home_mode_ = 0;
};

}  // namespace pkm
