#pragma once
// Rotopod: six constant-length struts whose lower joints ride carriages on one circle (Smirnov 2019,
// §1.2, §2.2.8, Fig. 15/44).
//
// Carriage j sits at A_j(φ_j) = (x_O + R·cos φ_j, y_O + R·sin φ_j, z_j): φ_j measured from the circle's
// diameter parallel to OX, z_j a constant (§2.2.8). The strut keeps |A_j(φ_j) − B_j| = L_j with B_j = p +
// R_p·b'_j, the model of §2.2.8, (39) corrected as (21). The closed-form IK (pkm's own), written about the
// point of the circle nearest B_j:
//   cos(φ_j − φ_near,j) = (R² + ρ_j² + Δz_j² − L_j²) / (2·R·ρ_j),   φ_near,j = atan2(y_B − y_O, x_B − x_O),
//   ρ_j = |(x_B, y_B) − (x_O, y_O)|,   Δz_j = z_j − z_B,
// has 0, 1 or 2 solutions; branch σ_j = +1 takes φ_near + arccos(…) (the carriage counter-clockwise, seen
// from +z, of the nearest point), −1 the other (σ = +1 is the "−" sign of atan2(d_y, d_x) ±
// arccos(rhs/|d|)). Implicit differentiation of |A(φ) − B|² = L² gives ∂φ/∂B = (A − B)/((A − B)·A'(φ)), A' =
// R·(−sin φ, cos φ, 0), infinite when the strut is perpendicular to the carriage's path (the two roots
// merge).
//
// Angles are radians inside and reported in the 360° window centred on the carriage's home angle, so they
// move continuously around the home pose (no jump at ±180°).
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct RotopodGeometry {
  Eigen::Vector2d circle_center_mm = Eigen::Vector2d::Zero();  ///< O*, base frame
  double circle_radius_mm = 0.0;                               ///< R_осн
  std::array<double, 6> joint_heights_mm{};                    ///< z_j of the carriage joints
  std::array<double, 6> strut_lengths_mm{};                    ///< L_j
  std::array<Eigen::Vector3d, 6> platform_joints_mm;           ///< b'_j, tool frame
  std::array<int, 6> branches{1, 1, 1, 1, 1, 1};               ///< σ_j = ±1
};

class Rotopod final : public Mechanism {
 public:
  Rotopod(const RotopodGeometry& geometry, AngleConvention convention, const Pose& home);

  MechanismType type() const override { return MechanismType::rotopod; }
  int actuator_count() const override { return 6; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override { return AxisMask::all(); }
  bool actuators_are_angles() const override { return true; }

  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode at these carriage positions (machine/carriage_assembly_modes.hpp;
  /// rotopod_assembly_modes.cpp), the machine's own labelled 0.
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// Carriage joints A_j(φ_j) and platform joints; the carriages turn with φ_j (mount_yaw_rad = φ_j); −1 when
  /// a strut cannot reach the circle.
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;
  /// Carriages run round the circle: r·(−sin φ, cos φ, 0) and r·(−cos φ, −sin φ, 0) per rad.
  void base_joint_motion(int strut, double actuator, Eigen::Vector3d& first,
                         Eigen::Vector3d& second) const noexcept override;
  /// Rows (g_j, (R·b'_j) × g_j), g_j = ∂φ_j/∂B_j (rad/mm): carriage angle rates from the twist.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// 6 × (carriage R on the circle, U, S) with constant-length struts.
  MechanismStructure structure() const override { return {"6-RUS (rotopod)", false, 14, {6, 6, 6, 0, 0}, 0}; }
  /// circle_center O (1 × [x, y] mm), circle_radius R (1 × 1 mm), joint_heights z1..z6 and strut_lengths
  /// L1..L6 (6 × 1 mm each), platform_joints_from_tool B1..B6 (tool frame, 6 × 3 mm). The branches stay.
  std::vector<GeometryGroup> geometry_parameters() const override;
  /// Keeps the home pose; the angle windows are centred on the new home angles.
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  const RotopodGeometry& geometry() const { return geometry_; }
  /// Carriage joint A_j at angle φ (rad).
  Eigen::Vector3d carriage_mm(int j, double angle_rad) const;
  /// The home angles φ_j: the centres of the windows the angles are reported in.
  const std::array<double, 6>& reference_angles_rad() const { return reference_rad_; }
  /// φ_j of a platform joint position and ∂φ_j/∂B, in the window centred on `centre_rad`; false when
  /// unreachable or singular (strut perpendicular to the carriage path).
  bool carriage_angle(int j, const Eigen::Vector3d& joint, double centre_rad, double& angle_rad,
                      Eigen::Vector3d& d_angle_dB) const;
  /// det of the strut-line matrix (unit strut directions and moments about the tool point, mm): the assembly
  /// mode's sign; 0 at a forward singularity or when unreachable.
  double strut_line_determinant(const Pose& pose) const;
  /// Sign of strut_line_determinant: the platform's assembly mode (changes only through a forward
  /// singularity).
  int assembly_mode(const Pose& pose) const;
  /// min_j |cos| of the angle between strut j and the tangent of its carriage's circle: 1 = strut along the
  /// tangent, 0 = strut perpendicular to it (an inverse singularity) or unreachable.
  double path_conditioning(const Pose& pose) const;

 private:
  Result<ActuatorVector> angles(const Pose& pose, const std::array<double, 6>& centres_rad) const;
  /// The carriage angles into `out`, each in the 2π window about its centre: −1, or the first carriage
  /// whose angle is undefined (its platform joint on the circle's axis) or whose strut cannot reach the
  /// circle.
  int carriage_angles(const Pose& pose, const std::array<double, 6>& centres_rad, double* out) const noexcept;

  RotopodGeometry geometry_;
  AngleConvention convention_;
  std::array<double, 6> reference_rad_{};
  int home_mode_ = 0;
};

/// Default home of a machine file without `home:`: tool point over the circle centre, no rotation, at the
/// height where the struts stand on average a quarter-turn from the nearest point of the circle (arccos
/// argument 0, the middle of the two-root range, far from both inverse singularities), platform above the
/// carriages.
Pose rotopod_default_home(const RotopodGeometry& geometry);

}  // namespace pkm
