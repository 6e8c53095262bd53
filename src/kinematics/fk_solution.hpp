#pragma once
// Forward kinematics' values: the solver's limits, one solution, and what an enumeration of all assembly
// modes saw.
#include <string>
#include <vector>

#include "core/pose.hpp"

namespace pkm {

/// Solver limits for forward kinematics (a parameter, never a hidden constant; STYLE habit 5).
struct FkOptions {
  double tolerance_mm = 1e-10;  ///< max |actuator residual| at convergence (mm, or rad for angular actuators)
  int max_iterations = 60;      ///< Newton iterations before giving up
  double min_rcond = 1e-13;  ///< smallest/largest LU pivot of the Jacobian below which it counts as singular
  /// Reject a solution in another assembly mode than the guess's: along a path the guess is the previous
  /// pose, so a change of mode means the solver jumped across a singularity or onto a mirrored assembly.
  bool require_same_branch = true;
  /// Threads an enumeration of all assembly modes (forward_all, assembly_modes) may use: 1 the caller's
  /// thread alone (for callers that already run many solves in parallel), 0 one per processor core.
  int threads = 1;
};

/// One forward-kinematics solution.
struct FkSolution {
  Pose pose;
  int iterations = 0;
  double residual_mm = 0.0;  ///< max |IK(pose) − actuators|
  int branch = 0;            ///< assembly-mode label; 0 = the home pose's mode
};

/// What an enumeration of assembly modes saw beyond the real solutions it returns, so that a user knows what
/// was not returned and why (Mechanism::assembly_modes). Counts are −1 where the method cannot see them.
struct AssemblyModeReport {
  std::string method;    ///< how the modes were found, in words
  int real = 0;          ///< real assembly modes returned
  int complex = -1;      ///< complex (non-real) solutions of the same equations
  int at_infinity = -1;  ///< solutions this geometry loses to infinity (special layouts)
  int singular = -1;     ///< solutions where two or more modes meet (or a continuum of poses)
  int failed = 0;        ///< paths or brackets that could not be followed to the end
};

struct AssemblyModes {
  std::vector<FkSolution> solutions;  ///< as forward_all()
  AssemblyModeReport report;
};

}  // namespace pkm
