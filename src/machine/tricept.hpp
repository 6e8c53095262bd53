#pragma once
// Tricept (§2.2.7): three telescopic struts from universal joints A_j on the base to spherical joints B_j
// on the manipulator flange, plus a passive central leg that slides through a cardan joint at the fixed point
// O. The cardan allows rotations α about x and β about the once-rotated y, never about the manipulator's own
// axis:
//   flange orientation B = Rx(α)·Ry(β),  tan α = −y/z,  tan β = x/√(y² + z²)   (34), (35), (36)
// with (x, y, z) = C − O, so that the flange axis B·e_z points from O to the characteristic point C.
//   L_j = |C + B·b'_j − A_j|                                                    (38), vector form
//
// Pose origin = the tool point, as for every pkm mechanism (hexapod: pose origin = tool point). The tool must
// lie on the manipulator axis, at a signed distance `tool_offset_mm` from C (positive away from O), so the
// tool point P, C and O are collinear and P alone fixes C and B. Controlled coordinates: x, y, z of the tool
// point; the three angles are dependent (complete_pose).
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct TriceptGeometry {
  std::array<Eigen::Vector3d, 3> base_joints_mm;      ///< universal-joint centres A_j, base frame
  std::array<Eigen::Vector3d, 3> platform_joints_mm;  ///< flange joints b'_j in the flange frame (origin C)
  Eigen::Vector3d center_joint_mm = Eigen::Vector3d::Zero();  ///< central cardan point O, base frame
  double tool_offset_mm = 0.0;  ///< tool point = C + tool_offset_mm · (flange axis)
};

/// Cardan angles of the flange and the centre point C for a tool point.
struct TriceptAxis {
  double alpha_rad = 0.0;                               ///< rotation about x (34)
  double beta_rad = 0.0;                                ///< rotation about the once-rotated y (35)
  double rho_mm = 0.0;                                  ///< |OC|, the extension of the central leg (33)
  Eigen::Vector3d center_mm = Eigen::Vector3d::Zero();  ///< C
};

class Tricept final : public Mechanism {
 public:
  /// `home_position_mm`: the home tool point. Fails when it is unreachable or singular.
  static Result<Tricept> create(const TriceptGeometry& geometry, AngleConvention convention,
                                const Eigen::Vector3d& home_position_mm);

  MechanismType type() const override { return MechanismType::tricept; }
  int actuator_count() const override { return 3; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override { return AxisMask::translations(); }

  Result<Pose> complete_pose(const Pose& pose) const override;
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode (tool points with these strut lengths): Newton from a fixed grid over the reachable
  /// half-space (tricept_assembly_modes.cpp), nearest to home first.
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  /// assembly_modes on a grid of `directions` (Fibonacci hemisphere) × `radii`: the tests check that a
  /// denser grid than the default finds nothing more.
  Result<AssemblyModes> assembly_modes_on_grid(const ActuatorVector& actuators, int directions,
                                               int radii) const;
  static constexpr int kAssemblyGridDirections = 300;
  static constexpr int kAssemblyGridRadii = 8;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// The three telescopic struts (universal base joints, spherical flange joints) at the completed pose; the
  /// central leg's cardan is not a strut joint and is not included.
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;
  /// The strut lengths' rows (u_j, (B_j − p) × u_j) at the completed pose. The platform can make only the
  /// twists its constraints allow (complete_pose); the rows hold for any twist, as if the platform were free.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// The tool point is controlled; the platform turns with the manipulator axis: (I; Ω) with Ω the angular
  /// velocity per unit tool-point velocity from (34)–(36).
  bool controlled_twists(const Pose& pose, TwistBasis& out) const noexcept override;
  /// 3 × (U, P, S) + central leg (U, P) fixed to the flange.
  MechanismStructure structure() const override { return {"3-UPS + UP", false, 9, {4, 4, 3, 0, 0}, 0}; }
  /// base_joints A1..A3 (base frame), platform_joints B1..B3 (flange frame, as in the machine file), 3 × 3
  /// mm, and center_joint O (1 × 3 mm). The tool offset is left out: moving it along the axis is the same as
  /// moving all three flange joints along it, so it is not identifiable beside them.
  std::vector<GeometryGroup> geometry_parameters() const override;
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  const TriceptGeometry& geometry() const { return geometry_; }
  /// The manipulator axis through a tool point; false when the point is out of reach (see complete_pose).
  bool axis_of(const Eigen::Vector3d& tool_point_mm, TriceptAxis& axis) const noexcept;

 private:
  Tricept(const TriceptGeometry& geometry, AngleConvention convention);

  /// Strut lengths and dL/d(tool point) at a tool point; false when it is out of reach.
  /// dω/dP: the platform's angular velocity per unit tool-point velocity along the manipulator axis.
  Eigen::Matrix3d angular_rate_per_tool_velocity(const Eigen::Vector3d& tool_point_mm,
                                                 const TriceptAxis& axis) const noexcept;
  bool evaluate(const Eigen::Vector3d& tool_point_mm, Eigen::Vector3d& lengths_mm,
                Eigen::Matrix3d* jacobian) const noexcept;

  TriceptGeometry geometry_;
  AngleConvention convention_;
  std::array<Eigen::Vector3d, 3> platform_tool_mm_;  ///< b'_j shifted to the tool frame
  int home_sign_ = 1;                                ///< sign of det(dL/dP) at home: the assembly mode
};

}  // namespace pkm
