#pragma once
// Every assembly mode of a general 6-6 Gough–Stewart platform by parameter homotopy (Morgan–Sommese): the 40
// solutions of one generic complex instance (the start system) are followed along a straight parameter path
// to the machine's real instance. Every solution of the target that is isolated is the end of one of these
// 40 paths, because 40 is the generic root count (the start instance is generic with probability one, and a
// complex straight path meets the discriminant, of real codimension two, with probability zero).
//
// The start system's 40 solutions are computed once by monodromy (stewart_start_by_monodromy: loops through
// random parameter values permute the solutions of the start instance, so that one known solution grows to
// all 40) and shipped as data (stewart_start_data.cpp, written by pkm_stewart_start_gen).
//
// The target is scaled (joints about their centroids, lengths by the machine's size) so that its parameters
// have the start instance's size. A path's end is a real pose when its Study coordinates are real up to one
// complex factor; the pose is returned unpolished (the mechanism polishes it with its own Newton).
#include <cstdint>
#include <vector>

#include "core/pose.hpp"
#include "kinematics/stewart_homotopy.hpp"

namespace pkm {

struct StewartStartSystem {
  Eigen::Vector4cd chart;
  StewartParameters parameters;
  std::vector<StudyPoint> roots;
};

/// Monodromy from a random instance built around one random solution: each loop goes through two random
/// parameter points and back, following every known solution; it stops after `quiet_loops` loops in a row
/// find nothing new once `expected` solutions are known, or after `max_loops`.
StewartStartSystem stewart_start_by_monodromy(std::uint64_t seed, int expected = 40, int max_loops = 60,
                                              int quiet_loops = 3);

/// The shipped start system (stewart_start_data.cpp).
const StewartStartSystem& stewart_start_system();

struct StewartModeCandidate {
  Pose pose;           ///< in the caller's frames and millimetres
  double imaginary;    ///< |Im| / |x| of the Study coordinates after the common complex factor is removed
  double pivot_ratio;  ///< of the Jacobian at the end (≈ 0: a multiple or non-isolated solution)
};

struct StewartAllModes {
  std::vector<StewartModeCandidate> real;  ///< the real endpoints (imaginary ≤ real_tolerance)
  int finite = 0;                          ///< paths that ended at a finite solution (real or complex)
  int complex = 0;                         ///< of which complex (not real)
  int at_infinity = 0;  ///< paths that diverged: solutions the target lost (special geometry)
  int singular = 0;     ///< finite endpoints with a singular Jacobian
  int failed = 0;       ///< paths whose step size collapsed before t = 1
  int retracked = 0;    ///< paths followed again with smaller steps after two ended at the same solution
  /// paths not followed because the followed ones and their conjugates already gave all 40 solutions (they
  /// are counted as finite and complex: each ends at one of the conjugates)
  int skipped = 0;
  int steps = 0;  ///< predictor–corrector steps over all paths
};

struct StewartAllModesOptions {
  PathTrackOptions tracking;
  /// An endpoint whose Study coordinates have |Im|/|x| at most this (after the common factor) is real.
  double real_tolerance = 1e-6;
  /// Stop following paths once the endpoints and their conjugates number 40 (StewartAllModes::skipped).
  bool stop_when_all_known = true;
  /// Threads following the paths (each path is independent): 1 this thread only, 0 one per processor core.
  int threads = 1;
};

/// All assembly modes for base joints A_j (base frame), platform joints b_j (platform/tool frame) and strut
/// lengths L_j, all in mm: |p + R b_j − A_j| = L_j.
StewartAllModes stewart_all_modes(const std::array<Eigen::Vector3d, 6>& base_mm,
                                  const std::array<Eigen::Vector3d, 6>& platform_mm,
                                  const std::array<double, 6>& lengths_mm,
                                  const StewartAllModesOptions& options = {});

/// Study coordinates of a real pose (unit e): for tests and for building instances around a known pose.
StudyPoint study_point_of(const Pose& pose);

}  // namespace pkm
