#pragma once
// Hexapod 6-UPS (Gough–Stewart platform), 6-6 or 6-3 layout, with the tool point as pose origin.
//   L_j = | p + R·b'_j − A_j |                      (Smirnov 2019, eq. 20/22, correct form; §2.2.3)
// A_j: base (universal) joint centres in the base frame; b'_j: platform (spherical) joint centres in the tool
// frame (platform frame shifted to the tool point). Pairwise-merged platform joints (6-3) are equal b'_j.
#include <array>

#include "kinematics/platform_newton.hpp"
#include "kinematics/strut_lengths.hpp"
#include "machine/base_plane.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

struct HexapodGeometry {
  std::array<Eigen::Vector3d, 6> base_joints_mm;
  std::array<Eigen::Vector3d, 6> platform_joints_mm;  ///< in the tool frame
};

/// The hexapod's FK state along a path: the platform solver's workspace (last factorisation, last solutions).
class HexapodFkWorkspace final : public FkWorkspace {
 public:
  using FkWorkspace::FkWorkspace;
  std::unique_ptr<FkWorkspace> clone() const override {
    auto copy = std::make_unique<HexapodFkWorkspace>(owner());
    copy->platform = platform;
    return copy;
  }
  void reset() override { platform.reset(); }
  void forget_path() override { platform.solutions_kept = 0; }
  PlatformFkWorkspace<6> platform;
};

class Hexapod final : public Mechanism {
 public:
  Hexapod(const HexapodGeometry& geometry, AngleConvention convention, const Pose& home);

  MechanismType type() const override { return MechanismType::hexapod; }
  int actuator_count() const override { return 6; }
  AngleConvention convention() const override { return convention_; }
  AxisMask controlled_axes() const override { return AxisMask::all(); }

  Result<ActuatorVector> inverse(const Pose& pose) const override;
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  /// Every assembly mode: the 40-path parameter homotopy of kinematics/stewart_all_modes.hpp, united with a
  /// 1-D scan for merged joints (6-3, or 3-6 for the inverse motion) (hexapod_assembly_modes.cpp).
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override;
  /// Base joints A_j and platform joints p + R·b'_j.
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override;
  /// The platform solver with the workspace's factorisation (a HexapodFkWorkspace from make_fk_workspace).
  Result<FkSolution> forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                  const FkOptions& options, FkWorkspace& workspace) const override;
  /// forward_warm without a message: no allocation, failing or not.
  bool forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                          FkWorkspace& workspace, FkSolution& out, ErrorCode& failure) const override;
  std::unique_ptr<FkWorkspace> make_fk_workspace() const override;
  /// strut_lengths(); false when a strut would have zero length (as inverse()).
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  bool actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                          double* out) const noexcept override;
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override {
    out = twist_jacobian(pose);
    return true;
  }
  /// One pass over the struts: each joint, length and direction computed once.
  int strut_state(const Pose& pose, StrutJointPoints& ends, double* actuators,
                  JacobianMatrix& twist_rows) const noexcept override;
  bool has_distance_actuators() const override { return true; }
  /// base_joints A1..A6 (base frame) and platform_joints_from_tool B1..B6 (tool frame), 6 × 3 mm each.
  std::vector<GeometryGroup> geometry_parameters() const override;
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;
  /// 6 × (U, P, S); base + platform + 12 strut parts.
  MechanismStructure structure() const override { return {"6-UPS", false, 14, {6, 6, 6, 0, 0}, 0}; }

  /// FK along a path: as forward(), reusing the factorisation kept in `workspace` by the previous call
  /// (one workspace per path; the first call factorises). The hot path of a servo loop.
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                             PlatformFkWorkspace<6>& workspace) const;
  /// The same, with the failure as data: false with `failure`, or with `other_mode` set when Newton converged
  /// in another assembly mode than the guess's (`out` then holds that solution). Never allocates.
  bool forward_quiet(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                     PlatformFkWorkspace<6>& workspace, FkSolution& out, PlatformFkFailure& failure,
                     bool& other_mode) const;

  /// Hot path: strut lengths of a pose, no checks, no allocation (all six at once: kinematics/strut_lengths).
  void strut_lengths(const Pose& pose, double* lengths_mm) const noexcept {
    six_strut_lengths(layout_, pose, lengths_mm);
  }
  /// Twist Jacobian (columns v, ω about the tool point), rows = unit strut vectors (Plücker lines).
  Eigen::Matrix<double, 6, 6> twist_jacobian(const Pose& pose) const noexcept;

  const HexapodGeometry& geometry() const { return geometry_; }
  bool is_six_three() const { return six_three_; }

  // Leg interface for solve_platform_fk.
  int leg_count() const { return 6; }
  const Eigen::Vector3d& platform_joint(int j) const { return geometry_.platform_joints_mm[j]; }
  bool leg_position(int j, const Eigen::Vector3d& joint, double& q) const {
    q = (joint - geometry_.base_joints_mm[j]).norm();
    return q > 0.0;
  }
  bool leg_value(int j, const Eigen::Vector3d& joint, double& q, Eigen::Vector3d& g) const {
    const Eigen::Vector3d d = joint - geometry_.base_joints_mm[j];
    q = d.norm();
    if (!(q > 0.0)) return false;
    g = d / q;
    return true;
  }

 private:
  /// Assembly-mode label (BasePlane): side of the base-joint plane of the platform joints and sign of det J.
  int assembly_mode(const Pose& pose) const;
  int assembly_mode(const Pose& pose, double jacobian_determinant) const;

  HexapodGeometry geometry_;
  /// The joints by coordinate, row k holding component k of the six (strut_lengths and strut_state work on
  /// all six struts at once, several per instruction).
  SixStrutLayout layout_;
  AngleConvention convention_;
  BasePlane base_plane_;
  int home_mode_ = 0;
  double home_determinant_ = 0.0;
  bool six_three_ = false;
};

}  // namespace pkm
