#pragma once
// The assembly-mode margin of a pose: how far the actuators may move from where they are before
// the machine, following them in its current assembly mode, meets a configuration where that mode can meet
// another one.
//
// Definition. At a pose X0 with actuator values q0 = IK(X0), let J(X) be the mechanism's square actuator
// Jacobian: the twist form (Mechanism::twist_jacobian, actuators × (v, ω)) where the mechanism controls all
// six coordinates and has one; otherwise d(actuators)/d(controlled coordinates) (Mechanism::jacobian) divided
// by the volume sqrt(det(TᵀT)) its coordinates give the platform's motion (T = Mechanism::controlled_twists,
// rotations times the platform size), so that a gimbal lock of the angle convention, where det J vanishes
// with T's rank, does not count. Where det J(X) = 0 the platform has a motion the locked actuators do not
// resist (a forward-kinematics, or "type II", singularity): there two assembly modes of the same actuator
// values merge, and moving the actuators through it can carry the machine into another mode. The margin is
//
//   m(X0) = min ‖q(X) − q0‖₂  over poses X with det J(X) = 0,
//
// over the singular configurations that bound X0's aspect (the connected set of regular poses around X0, in
// which the machine moves continuously in its current assembly mode), in mm (rad for angular actuators).
// Actuator values within m of q0 stay inside the image of that aspect near q0, where the forward kinematics
// of the current mode is a smooth, regular function: after a power loss or a homing error below m, forward
// kinematics warm-started from the last pose finds a pose of the current mode and has no other mode nearby to
// fall into. Change the actuators by more than m and the machine may reach a singular configuration and leave
// its mode. At a nearest singular configuration X*, q(X*) − q0 is normal to the image of the singular
// configurations: it is the left null vector of J(X*).
//
// The minimum is local, found by a local method from X0. SLSQP (NLopt) minimises ‖q(X) − q0‖² subject to
// det J(X)/det J(X0) = 0 (an O(1) equality constraint, tolerance `singular_det_ratio`), in pose coordinates
// preconditioned by J at X0 so that near X0 they are actuator changes (rotations of six-coordinate machines
// as rotation vectors about X0's orientation, otherwise the controlled coordinates), with central-difference
// gradients, inside a box of three times the nearest ray edge below. It starts from X0 and from the nearest
// of the first singular configurations on 2m + 1 rays from X0 (along −∇ det J and along ± each preconditioned
// coordinate, i.e. near X0 one actuator moving alone), whose distances also bound the margin. A configuration
// counts only if |det J(X*)| ≤ `singular_det_ratio` · |det J(X0)| and the straight line from X0 to it stays
// regular with det J of X0's sign (so X* bounds X0's aspect); where the line leaves the aspect first, the
// search restarts from there. The margin is the distance of the nearest configuration that counts: a nearer
// singular configuration that none of the starts leads to may exist, so the margin is an upper bound of the
// true distance, and equal to it where the singular surface near X0 is the one the starts see.
#include <limits>
#include <string>

#include "machine/mechanism.hpp"

namespace pkm::workspace {

struct ModesMarginOptions {
  /// A configuration counts as singular where |det J(X)| ≤ this · |det J(X0)| (the constraint's tolerance);
  /// X0 itself counts as singular (margin 0) where J(X0)'s smallest singular value is below this times its
  /// largest.
  double singular_det_ratio = 1e-9;
  /// The search stops when a step moves the (actuator-scaled) pose coordinates by less than this fraction of
  /// their size.
  double step_tolerance_rel = 1e-10;
  /// Objective evaluations of one SLSQP run (each start and restart has its own).
  int max_evaluations = 4000;
  /// Finite-difference step of the gradients: this fraction of Mechanism::platform_size_mm() (1 rad for
  /// angular actuators) in the preconditioned coordinates.
  double gradient_step_fraction = 1e-6;
  /// How often a search restarts from where the straight line from X0 to its result leaves X0's aspect first.
  int max_restarts = 3;
};

/// The assembly-mode margin at one pose.
struct AssemblyModeMargin {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  bool found = false;        ///< a singular configuration of X0's aspect was found
  double margin_mm = kNone;  ///< ‖q(X*) − q0‖₂: mm, or rad for angular actuators
  Pose pose;                 ///< X0, completed by the mechanism
  ActuatorVector actuators;  ///< q0
  Pose singular_pose;        ///< X*, the singular configuration found (X0 itself when X0 is singular)
  ActuatorVector singular_actuators;  ///< q(X*)
  double det_ratio = kNone;           ///< det J(X*)/det J(X0): ≈ 0 where found
  bool twist_form = false;  ///< J is the twist Jacobian (true) or the Jacobian in controlled coordinates
  int evaluations = 0;      ///< objective evaluations of all SLSQP runs
  int restarts = 0;         ///< restarts from where the line from X0 left its aspect
  /// Why nothing was found; where found, empty unless no search converged to a local minimum in X0's
  /// aspect and the margin is the nearest singular configuration found on a line from X0 (a plain bound).
  std::string note;
};

/// The margin at `pose` (completed by the mechanism first). Fails for a pose out of reach (unreachable)
/// and for a mechanism without a square actuator Jacobian (unsupported). A search that finds no singular
/// configuration succeeds with found = false and the reason in `note`.
Result<AssemblyModeMargin> assembly_mode_margin(const Mechanism& mechanism, const Pose& pose,
                                                const ModesMarginOptions& options = {});

/// det J at `pose` in the form the margin uses (see above); false where the pose is out of reach or J is not
/// square. For tests and reports that compare with the margin's own constraint.
bool margin_determinant(const Mechanism& mechanism, const Pose& pose, double& determinant);

}  // namespace pkm::workspace
