#pragma once
// Planar 2-DOF mechanism: two struts of variable length from base joints A_1, A_2 to one output joint B
// (Smirnov 2019, §2.1.1, Fig. 22).
//   L_j = |B − A_j|                                           (eq. 3)
//   dL_j/dt = [(x_B − x_Aj)·dx_B/dt + (y_B − y_Aj)·dy_B/dt] / L_j   (eq. 4, printed sign corrected)
// The pose is B itself: PoseVector (x, y, 0, 0, 0, 0); there is no platform, so no angle and no tool point.
// Forward kinematics is the circle–circle intersection (a stable form of eq. 5/6, with the k_1
// erratum irrelevant); its two solutions are mirror images about line A_1A_2, and the assembly mode is the
// side of that line (the source picks "B above A_1A_2").
#include <Eigen/Core>
#include <array>

#include "machine/mechanism.hpp"

namespace pkm {

struct Planar2Geometry {
  std::array<Eigen::Vector2d, 2> base_joints_mm;  ///< A_1, A_2 in the base frame
};

class Planar2 final : public Mechanism {
 public:
  /// `home_mm`: the output joint B at home; must not lie on line A_1A_2 (checked by the machine-file entry).
  Planar2(const Planar2Geometry& geometry, const Eigen::Vector2d& home_mm);

  MechanismType type() const override { return MechanismType::planar2; }
  int actuator_count() const override { return 2; }
  AngleConvention convention() const override { return AngleConvention::abc; }
  AxisMask controlled_axes() const override { return {{true, true, false, false, false, false}}; }

  /// Keeps x, y; z = 0 and no rotation (B is a point).
  Result<Pose> complete_pose(const Pose& pose) const override;
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// Hot IK: inverse() without its Result, false where inverse() fails; never allocates.
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  /// Closed form; the solution on the guess's side of line A_1A_2 (the home side if the guess is on the
  /// line).
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Both mirror solutions, the home side first (branch 0), then its mirror (branch 1).
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  /// 2 × 2, rows (B − A_j)ᵀ / L_j, columns (x, y) (eq. 4 corrected).
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// Rows ((B − A_j)ᵀ / L_j, 0, 0, 0, 0): B is a point, so the z and ω columns are zero.
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override;
  /// Base pins A_j in z = 0; both struts end at B, the tool point.
  int strut_ends(const Pose& pose, StrutJointPoints& out) const override;
  bool is_planar() const override { return true; }
  /// Base, two two-part struts; 5 one-DOF pairs (B joins both struts).
  MechanismStructure structure() const override {
    return {"2-RPR (planar, one output joint)", true, 5, {5, 0, 0, 0, 0}, 0};
  }
  /// base_joints A1, A2 (base frame, 2 × [x, y] mm).
  std::vector<GeometryGroup> geometry_parameters() const override;
  /// Keeps the home point B; its side of line A1A2 stays the assembly mode.
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  /// Hot path: strut lengths for B, no checks, no allocation.
  void strut_lengths(const Eigen::Vector2d& b_mm, double* lengths_mm) const noexcept {
    for (int j = 0; j < 2; ++j) lengths_mm[j] = (b_mm - geometry_.base_joints_mm[j]).norm();
  }
  /// Signed distance of B from line A_1A_2, positive on the left of A_1 → A_2 (mm). 0 = singular (eq. 78).
  double side_mm(const Eigen::Vector2d& b_mm) const noexcept {
    return normal_.dot(b_mm - geometry_.base_joints_mm[0]);
  }
  /// det J = sin of the angle between the struts (dimensionless); 0 when B is on line A_1A_2 (eq. 78).
  double jacobian_determinant(const Eigen::Vector2d& b_mm) const noexcept;

  const Planar2Geometry& geometry() const { return geometry_; }

 private:
  /// B for given lengths on one side (+1 left of A_1 → A_2, −1 right), or an error (unreachable, singular).
  Result<Eigen::Vector2d> intersect(const ActuatorVector& lengths_mm, int side,
                                    const FkOptions& options) const;
  Result<FkSolution> solution_at(const ActuatorVector& lengths_mm, int side, const FkOptions& options) const;

  Planar2Geometry geometry_;
  double base_distance_mm_;  ///< |A_1A_2|
  Eigen::Vector2d along_;    ///< unit vector A_1 → A_2
  Eigen::Vector2d normal_;   ///< along_ turned by +90°
  int home_side_ = 1;
};

}  // namespace pkm
