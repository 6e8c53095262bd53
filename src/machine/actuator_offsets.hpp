#pragma once
// Drive zero offsets (Smirnov 2019, §5.2.4): a drive's reading is its actuator's geometric value less a
// constant, because the drive's zero was set at some length (or carriage position, or angle) that was not
// measured exactly. With d_j the offset of drive j,
//   reading q_j = g_j(pose) − d_j,   i.e.   g_j = q_j + d_j,
// g_j the inner mechanism's value (the true strut length). ActuatorOffsets is a decorator: it is the inner
// mechanism in every respect except that its actuator values are the drives' readings. Jacobians do not
// change (a constant shift), nor does anything about the platform.
//
// Forward-kinematics workspaces are the inner mechanism's own (make_fk_workspace), so the inner solver's
// owner check accepts them and warm starts keep working through the decorator.
#include <memory>

#include "machine/mechanism.hpp"

namespace pkm {

class ActuatorOffsets final : public Mechanism {
 public:
  /// `offsets`: one per actuator of `inner` (mm, or rad for angular actuators).
  ActuatorOffsets(std::unique_ptr<Mechanism> inner, const ActuatorVector& offsets);

  MechanismType type() const override { return inner_->type(); }
  int actuator_count() const override { return inner_->actuator_count(); }
  AngleConvention convention() const override { return inner_->convention(); }
  AxisMask controlled_axes() const override { return inner_->controlled_axes(); }
  bool actuators_are_angles() const override { return inner_->actuators_are_angles(); }

  Result<Pose> complete_pose(const Pose& pose) const override { return inner_->complete_pose(pose); }
  /// The inner values less the offsets.
  Result<ActuatorVector> inverse(const Pose& pose) const override;
  /// The inner solve of the readings plus the offsets.
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                             const FkOptions& options = {}) const override;
  bool forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess, const FkOptions& options,
                          FkWorkspace& workspace, FkSolution& out, ErrorCode& failure) const override;
  Result<FkSolution> forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                  const FkOptions& options, FkWorkspace& workspace) const override;
  /// The inner mechanism's workspace (it owns it, so its forward_warm uses it).
  std::unique_ptr<FkWorkspace> make_fk_workspace() const override { return inner_->make_fk_workspace(); }
  Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                              const FkOptions& options = {}) const override;
  Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                       const FkOptions& options = {}) const override;
  bool actuator_values(const Pose& pose, double* out) const noexcept override;
  bool actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                          double* out) const noexcept override;
  Result<JacobianMatrix> jacobian(const Pose& pose) const override { return inner_->jacobian(pose); }
  bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept override {
    return inner_->twist_jacobian(pose, out);
  }
  bool controlled_twists(const Pose& pose, TwistBasis& out) const noexcept override {
    return inner_->controlled_twists(pose, out);
  }
  int strut_joints(const Pose& pose, StrutJointPoints& out) const override {
    return inner_->strut_joints(pose, out);
  }
  int strut_ends(const Pose& pose, StrutJointPoints& out) const override {
    return inner_->strut_ends(pose, out);
  }
  /// The inner motion at the geometric value: the reading plus the offset.
  void base_joint_motion(int strut, double actuator, Eigen::Vector3d& first,
                         Eigen::Vector3d& second) const noexcept override {
    inner_->base_joint_motion(strut, actuator + offsets_[strut], first, second);
  }
  /// The inner mechanism's groups followed by `actuator_offsets` (dL1..dLn, one column, mm or rad).
  std::vector<GeometryGroup> geometry_parameters() const override;
  /// The inner mechanism rebuilt from all groups but the last, with the last as the offsets.
  Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const override;

  bool is_planar() const override { return inner_->is_planar(); }
  bool has_distance_actuators() const override { return inner_->has_distance_actuators(); }
  double platform_size_mm() const override { return inner_->platform_size_mm(); }
  MechanismStructure structure() const override { return inner_->structure(); }

  const Mechanism& inner() const { return *inner_; }
  const ActuatorVector& offsets() const { return offsets_; }

 private:
  std::unique_ptr<Mechanism> inner_;
  ActuatorVector offsets_;
};

/// The key of the offsets' group.
inline constexpr std::string_view kActuatorOffsetsKey = "actuator_offsets";
/// The offsets' group: `actuator_offsets`, rows dL1..dLn, one column, in mm or (`angles`) rad.
GeometryGroup actuator_offsets_group(const ActuatorVector& offsets, bool angles);

/// `inner` with drive offsets `offsets` (one per actuator).
std::unique_ptr<Mechanism> with_actuator_offsets(std::unique_ptr<Mechanism> inner,
                                                 const ActuatorVector& offsets);

/// A copy of `m` whose geometry_parameters() end with `actuator_offsets`: m's clone when it has that group
/// already, else m wrapped with zero offsets. Fails for mechanisms without geometry groups (no clone).
Result<std::unique_ptr<Mechanism>> with_actuator_offset_parameters(const Mechanism& m);

}  // namespace pkm
