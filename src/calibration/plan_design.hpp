#pragma once
// Which poses to measure (Smirnov 2019, §5.2.4):
//  - seven_pose_plan: the dissertation's experiment. From home, strut 1 is changed by ΔL, then strut 2
//    additionally, … up to strut n (cumulative), the poses by forward kinematics: n + 1 poses, for the
//    hexapod seven, which split into six 7 × 7 systems, one per strut. Exactly determined, so nothing checks
//    it, and badly conditioned (the predicted accuracy says how badly).
//  - random_plan: poses uniform in a box around home (± translation on x, y, z, ± angle on the angles of the
//    mechanism's convention; only the controlled coordinates vary, the others follow by complete_pose),
//    rejected when out of reach or refused by the caller's limits check.
//  - d_optimal_plan: greedy D-optimal selection from random candidates: each step adds the candidate that
//    most increases log det of the information matrix JᵀJ in the identifiable subspace, then exchange passes
//    swap a chosen pose for a candidate while that increases it.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "calibration/identifiability.hpp"
#include "calibration/residuals.hpp"
#include "calibration/synthetic_measurements.hpp"
#include "core/pose.hpp"
#include "core/result.hpp"
#include "machine/mechanism.hpp"

namespace pkm::calibration {

struct PosePlan {
  std::string name;  ///< "seven_pose", "random", "d_optimal"
  std::vector<Pose> poses;
};

/// The caller's limits: true when the machine may go to `pose` with `actuators` (actuator ranges, joint
/// swings, conditioning: e.g. a Machine's checks). An empty function accepts every reachable pose.
using PoseFilter = std::function<bool(const Pose&, const ActuatorVector&)>;

/// A box of poses around home.
struct PoseBox {
  double translation_mm = 50.0;            ///< ± on x, y, z
  double angle_rad = 0.17453292519943295;  ///< ± on each angle (10°)
};

/// The dissertation's plan: home, then struts 1..n changed by `strut_change_mm` one after the other,
/// cumulatively (n + 1 poses). The source gives no ΔL; 50 mm moves the ch5 hexapod's platform about as far as
/// the default random box (all six struts +50 mm lift it ≈ 55 mm), and a larger change conditions it better.
/// Fails where a pose is unreachable, has no forward solution or is refused.
Result<PosePlan> seven_pose_plan(const Mechanism& nominal, double strut_change_mm = 50.0,
                                 const PoseFilter& accept = {});

/// `count` poses uniform in `box` around home, reproducible from `seed`. Fails when fewer than `count` poses
/// are accepted in 1000 × count draws.
Result<PosePlan> random_plan(const Mechanism& nominal, int count, const PoseBox& box, std::uint64_t seed,
                             const PoseFilter& accept = {});

struct DOptimalOptions {
  int candidates = 400;  ///< random poses to choose from
  PoseBox box;
  std::uint64_t seed = 1;
  PoseFilter accept;
  int exchange_passes = 3;  ///< Fedorov exchange passes after the greedy selection (0: none)
  ResidualOptions residuals;
  IdentifiabilityOptions identifiability;
};

/// `count` poses chosen D-optimally for measuring with `setup`. Fails for count < 1 or too few candidates.
Result<PosePlan> d_optimal_plan(const Mechanism& nominal, const MeasurementSetup& setup, int count,
                                const DOptimalOptions& options = {});

}  // namespace pkm::calibration
