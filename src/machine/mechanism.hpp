#pragma once
// One interface for every mechanism, so that every stage of pkm works for all of them.
// The value types it trades in (actuator vectors, FK options and solutions, axis masks, strut joints) are
// the kinematics kernel's, in kinematics/; this header includes them, so its users need no other include.
//
// Pose coordinates are the six of PoseVector (x, y, z mm; three angles in the mechanism's convention, rad).
// A mechanism controls some of them (`controlled_axes`); reduced-DOF mechanisms compute the others
// (`complete_pose`). Actuator coordinates are strut lengths or carriage positions in mm, or, for carriages on
// a circle, angles in rad (`actuator_unit`).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "kinematics/actuator_vector.hpp"
#include "kinematics/axis_mask.hpp"
#include "kinematics/fk_solution.hpp"
#include "kinematics/strut_joint_points.hpp"
#include "machine/mechanism_structure.hpp"
#include "machine/mechanism_type.hpp"

namespace pkm {

/// A group of geometric constants of a mechanism that calibration can identify: `rows` × `columns`
/// numbers, row-major, e.g. the six base joints, 6 × 3 mm. `key` is also the key that carries the group in a
/// machine file's `calibration:` section (io/calibration_file.cpp), so a calibrated machine file is the
/// drawing plus the identified groups.
struct GeometryGroup {
  std::string key;                        ///< e.g. "base_joints"; unique within a mechanism
  std::string row_symbol;                 ///< how rows are named in messages: "A" → A1, A2, …
  std::vector<std::string> column_names;  ///< e.g. {"x", "y", "z"}; {""} for one number per row
  std::string unit;                       ///< "mm", "rad", …
  int rows = 0;
  std::vector<double> values;  ///< rows × column_names.size(), row-major
  int columns() const { return static_cast<int>(column_names.size()); }
};

class Mechanism;

/// State a mechanism carries from one forward-kinematics call to the next along a path (Pinocchio's data to
/// the mechanism's model): made once, at set-up, by Mechanism::make_fk_workspace, so that the servo-loop form
/// Mechanism::forward_warm never allocates. A workspace belongs to the
/// mechanism that made it; given to another, it is ignored (that call solves as the plain forward does).
class FkWorkspace {
 public:
  explicit FkWorkspace(const Mechanism* owner) : owner_(owner) {}
  virtual ~FkWorkspace() = default;
  FkWorkspace(const FkWorkspace&) = delete;
  FkWorkspace& operator=(const FkWorkspace&) = delete;

  /// An independent copy with the same state (allocates: for copying whole trackers, never per tick).
  virtual std::unique_ptr<FkWorkspace> clone() const { return std::make_unique<FkWorkspace>(owner_); }
  /// Forgets everything: the next call starts from its guess with a fresh factorisation.
  virtual void reset() {}
  /// Forgets the path (no extrapolation from earlier solutions) but keeps a factorisation: for many trial
  /// solves around one pose (the estimating function's candidates), which are no path.
  virtual void forget_path() {}
  const Mechanism* owner() const { return owner_; }

 private:
  const Mechanism* owner_;
};

class Mechanism {
 public:
  virtual ~Mechanism() = default;

  virtual MechanismType type() const = 0;
  virtual int actuator_count() const = 0;
  /// The convention of the angle coordinates of PoseVector (planar mechanisms: abc, φ is angle 3 = C).
  virtual AngleConvention convention() const = 0;
  virtual AxisMask controlled_axes() const = 0;
  /// "mm" for lengths and carriage positions, "rad" for angular actuators (shown as degrees to users).
  virtual bool actuators_are_angles() const { return false; }

  /// Fills in the coordinates the mechanism does not control, keeping the controlled ones.
  virtual Result<Pose> complete_pose(const Pose& pose) const { return pose; }
  /// Inverse kinematics; uses only the controlled coordinates of `pose`.
  virtual Result<ActuatorVector> inverse(const Pose& pose) const = 0;
  /// Forward kinematics from a guess (warm start), in the assembly mode of the guess.
  virtual Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& guess,
                                     const FkOptions& options = {}) const = 0;
  /// The servo-loop form of forward(): warm-started from the state kept in `workspace` by the previous call
  /// (hexapods: the previous factorisation and an extrapolated start, platform_newton.hpp). Does not allocate
  /// when it succeeds. The default keeps no state and solves as forward() does.
  /// (A name of its own, not a forward() overload: mechanisms override forward() without hiding this.)
  virtual Result<FkSolution> forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                          const FkOptions& options, FkWorkspace& workspace) const;
  /// forward_warm for a real-time servo loop (LinuxCNC's module): true with `out`, or false with the reason
  /// in `failure` and no message. The hexapods (and drive offsets over them) neither allocate nor throw,
  /// failing or not; the default calls forward_warm, so elsewhere a failure allocates its message (and drops
  /// it).
  virtual bool forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess,
                                  const FkOptions& options, FkWorkspace& workspace, FkSolution& out,
                                  ErrorCode& failure) const;
  /// A workspace for forward_warm (allocates: call at set-up, never per tick).
  virtual std::unique_ptr<FkWorkspace> make_fk_workspace() const;
  /// All assembly modes, where the mechanism can enumerate them: the real poses that give these actuator
  /// values, each polished by Newton and labelled (FkSolution::branch), nearest to home first.
  virtual Result<std::vector<FkSolution>> forward_all(const ActuatorVector& actuators,
                                                      const FkOptions& options = {}) const;
  /// forward_all with what the enumeration saw besides (complex solutions, solutions lost to infinity,
  /// singular ones). The default reports the solutions of forward_all only.
  virtual Result<AssemblyModes> assembly_modes(const ActuatorVector& actuators,
                                               const FkOptions& options = {}) const;
  /// Hot-path inverse kinematics: writes actuator_count() values to `out` (mm, or rad for angular actuators)
  /// and returns true; false when the pose is out of reach (`out` unspecified). Builds no Result and no
  /// message: it runs at every interpolation period. The default calls inverse(), which allocates only when
  /// it fails.
  virtual bool actuator_values(const Pose& pose, double* out) const noexcept;
  /// actuator_values at the pose of six coordinates (x, y, z in mm, three angles in rad in `convention`), as
  /// a controller hands them over (LinuxCNC's EmcPose): the values of
  /// actuator_values(pose_from_vector(convention, coordinates), out), which the default calls (bit for bit).
  /// The hexapod goes from the coordinates to its lengths in one kernel that turns the joints by the three
  /// elementary rotations instead of forming the matrix (kinematics/strut_lengths.hpp): equal to rounding.
  virtual bool actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                                  double* out) const noexcept;
  /// d(actuators)/d(controlled coordinates), angle rates in rad in the mechanism's convention.
  virtual Result<JacobianMatrix> jacobian(const Pose& pose) const = 0;
  /// Twist form of the Jacobian: actuator rates from the platform twist (tool-point velocity v mm/s and
  /// base-frame angular velocity ω rad/s), actuator_count() × 6 with columns (v, ω), independent of any angle
  /// convention. Its transpose maps actuator forces to the wrench on the platform (statics). For a
  /// reduced-DOF mechanism a row is the gradient of that actuator's value over all six platform motions as if
  /// the platform were free (the constraints are not in it; they are what complete_pose() solves), so only
  /// twists the mechanism allows are meaningful. Writes `out` and returns true; false when the pose is out of
  /// reach, or when the mechanism has no twist form (the default). Never allocates.
  virtual bool twist_jacobian(const Pose& pose, JacobianMatrix& out) const noexcept;
  /// How the platform moves when one controlled coordinate changes: column c is the twist (tool-point
  /// velocity v, base-frame angular velocity ω) per unit rate of the c-th controlled coordinate, in the
  /// column order of jacobian(). The coordinates a reduced-DOF mechanism does not control follow through its
  /// constraints (differentiated, not stepped), so these are the twists it allows: twist_jacobian() · T =
  /// jacobian(), and Tᵀ turns a wrench into generalised forces (statics, dynamics). The default, for
  /// mechanisms whose uncontrolled coordinates stay fixed: [I 0; 0 E(angles)] restricted to the controlled
  /// coordinates (ω = E · angle rates, core/rotation.hpp). False when the pose is out of reach or the
  /// constraints are singular there. Never allocates.
  virtual bool controlled_twists(const Pose& pose, TwistBasis& out) const noexcept;
  /// The passive joints at both ends of every strut at `pose` (reduced-DOF mechanisms complete the pose
  /// first). Returns the number of struts filled in, 0 for mechanisms without swinging passive joints (planar
  /// pin joints), −1 when the pose is out of reach (a carriage cannot reach its strut, or the pose cannot be
  /// completed). Never allocates for a reachable pose: it runs at every planning sample.
  virtual int strut_joints(const Pose& /*pose*/, StrutJointPoints& /*out*/) const { return 0; }
  /// Both ends of every strut at `pose` (the leg geometry for drawing, statics and stiffness: directions and
  /// lengths follow from the points): strut_joints(), and for mechanisms without swinging passive joints (the
  /// planar pin joints) their base and platform pins in z = 0. Same return values as strut_joints().
  virtual int strut_ends(const Pose& pose, StrutJointPoints& out) const { return strut_joints(pose, out); }
  /// The struts' kinematics at one pose in one pass: strut_ends(), actuator_values() and twist_jacobian()
  /// (Pinocchio's forward kinematics with the joint Jacobians). One call because the time-domain dynamics
  /// ask all three at every right-hand side (~17 000 times per simulated second). Returns strut_ends()'s
  /// count, or −1 when any of the three fails. The default makes the three calls; a mechanism whose three
  /// share their work (the struts' directions) overrides it. Never allocates for a reachable pose.
  virtual int strut_state(const Pose& pose, StrutJointPoints& ends, double* actuators,
                          JacobianMatrix& twist_rows) const noexcept;

  /// How the base-side joint of strut j moves with its own actuator at value `actuator` (mm, or rad): the
  /// first and second derivatives ∂A_j/∂q_j and ∂²A_j/∂q_j² in the base frame (dynamics: the carriages' and
  /// the struts' lower ends' velocities and accelerations). Zero for joints fixed to the base (the default);
  /// a carriage on a straight guide has (e_j, 0), one on a circle the tangent and the centripetal vectors.
  /// Mechanisms whose base joints move carry struts of constant length.
  virtual void base_joint_motion(int /*strut*/, double /*actuator*/, Eigen::Vector3d& first,
                                 Eigen::Vector3d& second) const noexcept {
    first.setZero();
    second.setZero();
  }

  /// The geometric constants calibration may identify, in a fixed order (empty: none). Values are in the
  /// frames the mechanism computes in (platform-side points: the tool frame, from the tool point, platform
  /// axes).
  virtual std::vector<GeometryGroup> geometry_parameters() const { return {}; }
  /// The same mechanism (convention, home, assembly mode) with other values of geometry_parameters():
  /// `groups` has the same keys and shapes in the same order. Fails for a mismatch and for mechanisms without
  /// groups.
  virtual Result<std::unique_ptr<Mechanism>> with_geometry(const std::vector<GeometryGroup>& groups) const;

  // Queries that replace tests of the mechanism's type: the stages ask what they need, not what it is.

  /// Planar mechanisms move in the base xy plane and turn about z only (φ is angle 3).
  virtual bool is_planar() const { return false; }
  /// True where every actuator is the distance between a base-fixed point and a platform-fixed point, with
  /// the whole pose free: then along a straight line or flat arc at constant orientation the actuator laws
  /// are the closed √(quadratic) and √(Fourier) models of Smirnov 2019 (interpolation/methods/strut_laws).
  virtual bool has_distance_actuators() const { return false; }
  /// The length that turns a platform rotation (rad) into a joint displacement (mm): scales the angle columns
  /// of Jacobians so that their determinants compare across poses. The default: the mean distance of the
  /// platform joints from the tool point at home (strut_joints), 100 mm without joints.
  virtual double platform_size_mm() const;
  /// Links and kinematic pairs, for the mobility formula (machine/mobility.hpp).
  virtual MechanismStructure structure() const { return {}; }

  /// The pose the machine starts from; FK without a guess starts here. Set once, at construction: mechanisms
  /// derive state from it (the home assembly mode, branch choices), so there is deliberately no setter.
  const Pose& home() const { return home_; }

 protected:
  Pose home_;
};

/// The twist Jacobian of struts whose actuators are their lengths |B_j − A_j|: row j = (u_j, (B_j − p) × u_j)
/// with u_j the unit strut vector and p the tool point of the (completed) pose. False when a strut has zero
/// length. For Mechanism::twist_jacobian overrides.
bool strut_length_twist_jacobian(const StrutJointPoints& joints, int count,
                                 const Eigen::Vector3d& tool_point_mm, JacobianMatrix& out) noexcept;

/// The twist Jacobian of actuators whose value depends on one platform joint each (carriages, glides, the
/// refined hexapod's legs): row j = (g_j, a_j × g_j), with a_j = R·(joint j in the tool frame) the joint's
/// arm from the tool point and g_j the gradient of actuator j's value over the joint's base-frame position,
/// from `gradient(j, joint_mm, g)` (false: out of reach, and so is the result). For Mechanism::twist_jacobian
/// overrides; never allocates.
template <class Joints, class Gradient>
bool joint_gradient_twist_jacobian(const Pose& pose, int count, const Joints& platform_joints_mm,
                                   Gradient&& gradient, JacobianMatrix& out) noexcept {
  out.resize(count, 6);
  for (int j = 0; j < count; ++j) {
    const Eigen::Vector3d arm = pose.rotation * platform_joints_mm[j];
    Eigen::Vector3d g;
    if (!gradient(j, Eigen::Vector3d(arm + pose.position_mm), g)) return false;
    out.template block<1, 3>(j, 0) = g.transpose();
    out.template block<1, 3>(j, 3) = arm.cross(g).transpose();
  }
  return true;
}

/// The twists per unit rate of all six pose coordinates at `pose`: [I 0; 0 E(angles)] (6 × 6), with E the
/// angular-velocity matrix of the convention. For Mechanism::controlled_twists overrides.
Eigen::Matrix<double, 6, 6> coordinate_twists(AngleConvention convention, const Pose& pose) noexcept;

/// Checks that `groups` have the keys and shapes of `expected` (for with_geometry overrides): an error naming
/// the first group that differs, or success.
Status check_geometry_groups(const std::vector<GeometryGroup>& expected,
                             const std::vector<GeometryGroup>& groups);
/// Row `row` of a group as a 3-vector (groups with three columns).
Eigen::Vector3d group_point(const GeometryGroup& group, int row);
/// A group of `points` with symbol `row_symbol`, columns x, y, z, in mm.
GeometryGroup point_group(std::string key, std::string row_symbol, const Eigen::Vector3d* points, int count);

/// The error of a forward-kinematics solve that found `solution` in another assembly mode than its guess's.
Error another_assembly_mode_error(const Pose& solution);

/// Names of the controlled coordinates, e.g. {"x","y","z","A","B","C"} or {"x","y","phi"}.
std::vector<std::string> controlled_coordinate_names(const Mechanism& mechanism);
/// All six coordinate names of the convention (planar: x, y, z, -, -, phi).
std::array<std::string, 6> pose_coordinate_names(const Mechanism& mechanism);

}  // namespace pkm
