#pragma once
// Glide machines: constant-length struts whose lower ends ride carriages on straight guides (Smirnov §1.2,
// §2.2.8; Rusanov et al.). Six guides (hexaglide) move a 6-DOF platform; three guides whose carriages each
// carry a parallelogram pair of struts (triglide, e.g. the pyramidal SFVPK-4) move a platform that only
// translates.
//
// Carriage j sits at C_j = P_j + s_j·e_j (P_j guide point, e_j unit guide direction, s_j the actuator in mm).
// With the platform joint B_j = p + R·b'_j, the constant strut length l_j gives the sphere–line intersection
//   |B_j − P_j − s_j·e_j|² = l_j²   ⇒   s_j = e_j·w_j + σ_j·√(l_j² − |w_j − (e_j·w_j)·e_j|²),   w_j = B_j −
//   P_j,
// σ_j = ±1 the branch: +1 is the root further along e_j (Rusanov et al.: the branch stays fixed, so
// the carriage moves continuously). Implicit differentiation of the constraint gives ∂s_j/∂B_j = (B_j −
// C_j)/((B_j − C_j)·e_j), infinite when the strut is perpendicular to its guide (the two roots merge: an
// inverse singularity).
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct GlideGeometry {
  int count = 6;                                      ///< 6 (hexaglide, 6 DOF) or 3 (triglide, translations)
  std::array<Eigen::Vector3d, 6> guide_points_mm;     ///< P_j, base frame
  std::array<Eigen::Vector3d, 6> guide_directions;    ///< e_j, base frame (normalised by the constructor)
  std::array<double, 6> strut_lengths_mm{};           ///< l_j
  std::array<Eigen::Vector3d, 6> platform_joints_mm;  ///< b'_j, tool frame
  std::array<int, 6> branches{1, 1, 1, 1, 1, 1};      ///< σ_j = ±1
};

class Glide final : public Mechanism {
 public:
  Glide(const GlideGeometry& geometry, AngleConvention convention, const Pose& home);

  MechanismType type() const override { return MechanismType::glide; }
  int actuator_count() const override { return geometry_.count; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override { return rotates() ? AxisMask::all() : AxisMask::translations(); }

  /// Three-guide machines keep the platform parallel to the base frame: the rotation becomes the identity.
  Result<Pose> complete_pose(const Pose& pose) const override;
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode at these carriage positions (machine/carriage_assembly_modes.hpp;
  /// glide_assembly_modes.cpp), the machine's own labelled 0.
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// Carriage joints C_j (on the branch's root) and platform joints; −1 when a strut cannot reach its guide.
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;
  /// Carriages slide along straight guides: (e_j, 0).
  void base_joint_motion(int strut, double actuator, Eigen::Vector3d& first,
                         Eigen::Vector3d& second) const noexcept override {
    (void)actuator;
    first = geometry_.guide_directions[strut];
    second.setZero();
  }
  /// Rows (g_j, (R·b'_j) × g_j), g_j = ∂s_j/∂B_j. A triglide's platform cannot turn (its orientation is held
  /// by the parallelograms): its ω columns say how the carriages would move if it could, and only its v
  /// columns meet twists it can make.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  MechanismStructure structure() const override;
  /// guide_points P1..Pn (base frame, n × 3 mm), strut_lengths L1..Ln (n × 1 mm) and
  /// platform_joints_from_tool B1..Bn (tool frame, n × 3 mm). The guide directions stay fixed (directions,
  /// not points); so do the branches.
  std::vector<GeometryGroup> geometry_parameters() const override;
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  bool rotates() const { return geometry_.count == 6; }
  const GlideGeometry& geometry() const { return geometry_; }
  /// The carriage position of a carriage j in the base frame.
  Eigen::Vector3d carriage_mm(int j, double s_mm) const {
    return geometry_.guide_points_mm[j] + s_mm * geometry_.guide_directions[j];
  }
  /// Sign of det of the strut-line matrix (rows: unit strut directions and their moments about the tool
  /// point): the platform's assembly mode; it changes only through a forward singularity. 0 when singular.
  int assembly_mode(const Pose& pose) const;
  /// det of the strut-line matrix (unit directions; moments in mm), 0 at a forward singularity.
  double strut_line_determinant(const Pose& pose) const;
  /// min_j |cos| of the angle between strut j and its guide: 1 = along the guide, 0 = perpendicular (an
  /// inverse singularity, the carriage speed becomes infinite); 0 also when a strut cannot reach its guide.
  double guide_conditioning(const Pose& pose) const;
  /// max_j | |cos| of the strut-to-guide angle − cos 45° |; +∞ when a strut cannot reach its guide.
  double angle_deviation_from_45(const Pose& pose) const;

  // Leg interface for solve_platform_fk.
  int leg_count() const { return geometry_.count; }
  const Eigen::Vector3d& platform_joint(int j) const { return geometry_.platform_joints_mm[j]; }
  bool leg_value(int j, const Eigen::Vector3d& joint, double& q, Eigen::Vector3d& g) const;

 private:
  Pose fixed_orientation(const Pose& pose) const;
  /// The carriage positions into `out`: −1, or the first carriage whose strut cannot reach its guide.
  int carriage_positions(const Pose& pose, double* out) const noexcept;

  GlideGeometry geometry_;
  AngleConvention convention_;
  int home_mode_ = 0;
};

/// Default home of a machine file without `home:`: no rotation, the platform-joint centroid over the
/// guide-point centroid, at the height where every strut is as near 45° to its guide as can be (min over z of
/// the worst deviation), halfway between the inverse singularity (90°) and a strut along its guide; for
/// guides parallel to z, where the angles do not depend on the height, at the height where the carriages are
/// nearest their guide points (min over z of max_j |s_j|). Scanned over ±2 strut lengths; of equal heights
/// the lower.
Result<Pose> glide_default_home(const GlideGeometry& geometry, AngleConvention convention);

}  // namespace pkm
