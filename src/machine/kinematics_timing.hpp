#pragma once
// Self-timing of a mechanism's kinematics, for `pkm bench kinematics`: an integrator can see on the target
// controller whether IK and FK fit its servo period. (The Google Benchmark programs in bench/ are the
// developers' measurement; this is the user's.)
#include <cstdint>

#include "machine/mechanism.hpp"

namespace pkm {

struct KinematicsTimingOptions {
  int ik_poses = 100000;
  double ik_range_mm = 20.0, ik_range_deg = 10.0;
  int path_poses = 20000;  ///< warm FK along a smooth path with 0.1 mm / 0.01° steps
  int cold_poses = 10000;
  double cold_range_mm = 50.0, cold_range_deg = 20.0;
  std::uint64_t seed = 1;
};

struct KinematicsTiming {
  double ik_ns_per_pose = 0.0;  ///< hot IK (Mechanism::actuator_values) from angles, conversion included
  double fk_us_per_solve_warm = 0.0;  ///< Mechanism::forward_warm with the mechanism's workspace
  double fk_iterations_warm = 0.0;
  double fk_converged_warm = 0.0;  ///< fraction converged to the right pose (1e-6 mm)
  double fk_us_per_solve_cold = 0.0;
  double fk_iterations_cold = 0.0;
  double fk_converged_cold = 0.0;  ///< fraction converged to the right pose from home
};

/// A random pose around `centre`: controlled translations ± range_mm, controlled angles ± range_rad.
Pose random_pose_near(const Mechanism& mechanism, const Pose& centre, double range_mm, double range_rad,
                      std::uint64_t& state);

KinematicsTiming time_kinematics(const Mechanism& mechanism, const KinematicsTimingOptions& options);

}  // namespace pkm
