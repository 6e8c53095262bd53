#pragma once
// Spatial tripod 3-RPS (§2.2.6, §2.3.4): three struts of variable length L_j, each on a revolute joint A_j
// of the base with a horizontal axis a_j (eq. 31) and a spherical joint B_j on the platform.
//   L_j = |B_j − A_j|,  B_j = p + R·b'_j                                   (29), (32)
//   a_j · (B_j − A_j) = 0   (strut j stays in the plane through A_j perpendicular to a_j)   (31)
// p is the tool point (pose origin), b'_j the platform joints in the tool frame.
//
// Three DOF: the controlled coordinates are z and the two tilts, i.e. the angles that are not the rotation
// about z: abc → (z, A, B), krylov → (z, ϑ, γ). In both conventions R = Rz(φ)·T(tilts) with φ = C (abc) or
// φ = −ψ (krylov); euler_zxz has no such split and is rejected. x, y and φ are dependent (complete_pose).
//
// Forward kinematics uses the joint-angle parametrisation of Smirnov 2019, §2.3.4:
//   B_j(t_j) = A_j + L_j·(cos t_j·e_z + sin t_j·w_j),  w_j = a_j × e_z,
// (t_j = rotation of strut j about a_j away from vertical), and solves the three rigid distances |B_i − B_k|.
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct TripodGeometry {
  std::array<Eigen::Vector3d, 3> base_joints_mm;      ///< revolute joint centres A_j, base frame
  std::array<Eigen::Vector3d, 3> base_axes;           ///< revolute axes a_j, unit and horizontal, base frame
  std::array<Eigen::Vector3d, 3> platform_joints_mm;  ///< spherical joint centres b'_j in the tool frame
};

/// x, y and the yaw φ that satisfy the three plane constraints (31) for given z and tilts.
struct TripodDependents {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double yaw_rad = 0.0;  ///< φ of R = Rz(φ)·T
};

class Tripod final : public Mechanism {
 public:
  /// `home` is completed here: its yaw picks which of the two yaw branches of (31) the machine uses (the one
  /// nearer the given yaw); x, y and the yaw are then recomputed. Fails when the home is unreachable or
  /// singular.
  static Result<Tripod> create(const TripodGeometry& geometry, AngleConvention convention,
                               const PoseVector& home);

  MechanismType type() const override { return MechanismType::tripod; }
  int actuator_count() const override { return 3; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override;

  Result<Pose> complete_pose(const Pose& pose) const override;
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// Revolute base joints A_j and spherical platform joints, at the completed pose.
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;
  /// The strut lengths' rows (u_j, (B_j − p) × u_j) at the completed pose. The platform can make only the
  /// twists its constraints allow (complete_pose); the rows hold for any twist, as if the platform were free.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// x, y and the yaw follow z and the tilts through the plane constraints (31), differentiated implicitly.
  bool controlled_twists(const Pose& pose, TwistBasis& out) const noexcept override;
  /// 3 × (R, P, S).
  MechanismStructure structure() const override { return {"3-RPS", false, 8, {6, 0, 3, 0, 0}, 0}; }
  /// base_joints A1..A3 (base frame) and platform_joints_from_tool B1..B3 (tool frame), 3 × 3 mm each. The
  /// revolute axes stay fixed: they are directions, and constraint (31) needs them horizontal.
  std::vector<GeometryGroup> geometry_parameters() const override;
  /// Through create() from the home's controlled coordinates and yaw, so the yaw branch stays the home's.
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  const TripodGeometry& geometry() const { return geometry_; }
  /// Strut lengths of a complete pose, no completion, no checks.
  Eigen::Vector3d strut_lengths(const Pose& pose) const noexcept;
  /// Plane-constraint residuals a_j·(B_j − A_j) of a pose, mm (zero for a complete pose).
  Eigen::Vector3d plane_residuals_mm(const Pose& pose) const noexcept;

  // Joint-angle form used by forward kinematics (§2.3.4).
  Eigen::Vector3d joint_at(int j, double length_mm, double angle_rad) const noexcept;
  double joint_angle_of(int j, const Eigen::Vector3d& point_mm) const noexcept;
  /// The rigid-body pose through three platform-joint positions (Eigen::umeyama on the three points).
  Pose pose_from_joints(const std::array<Eigen::Vector3d, 3>& joints_mm) const noexcept;
  /// At a complete pose: the twists per unit rate of all six coordinates, and the rates of the dependent
  /// coordinates (x, y, yaw) per unit rate of the controlled ones (z and the tilts). False where the plane
  /// constraints are singular (the two yaw branches meet) or a strut has zero length.
  bool dependent_rates(const Pose& complete, Eigen::Matrix<double, 6, 6>& coordinate_twist,
                       Eigen::Matrix3d& dependent_per_controlled) const noexcept;
  /// FK residuals |B_i − B_k|² − d_ik² for the pairs (1,2), (2,3), (3,1) and their derivatives by t.
  void distance_equations(const Eigen::Vector3d& lengths_mm, const Eigen::Vector3d& angles_rad,
                          Eigen::Vector3d& f, Eigen::Matrix3d& df_dt) const noexcept;

 private:
  Tripod(const TripodGeometry& geometry, AngleConvention convention);

  /// Dependent coordinates of the yaw branch `branch` (±1) at the tilt matrix T; false if no yaw fits.
  bool solve_dependents(const Eigen::Matrix3d& tilt, int branch, TripodDependents& out) const noexcept;
  /// Coefficients of the yaw equation α cos φ + β sin φ = γ left after eliminating x, y from (31).
  Eigen::Vector3d yaw_equation(const Eigen::Matrix3d& tilt) const noexcept;
  int yaw_branch_of(const Pose& pose) const noexcept;
  int assembly_mode(const Pose& pose, const Eigen::Vector3d& lengths_mm) const noexcept;
  Eigen::Matrix3d tilt_of(const PoseVector& coordinates) const;
  Pose pose_of(PoseVector coordinates, const TripodDependents& d) const;

  TripodGeometry geometry_;
  AngleConvention convention_;
  std::array<Eigen::Vector3d, 3> plane_side_;  ///< w_j = a_j × e_z: strut direction at t = 90° (t = 0: e_z)
  std::array<double, 3> platform_distance_mm_{};  ///< d_12, d_23, d_31
  Eigen::Vector3d null_{};                        ///< left null vector of the 3×2 matrix [l_j m_j]
  Eigen::Matrix<double, 2, 3> xy_solve_{};        ///< least-squares inverse of [l_j m_j]
  Eigen::Vector3d base_centroid_mm_{};
  Eigen::Vector3d base_normal_{};
  int yaw_branch_ = -1;
  int home_mode_ = 0;
};

}  // namespace pkm
