#pragma once
// The planning grid: samples along the path where inverse kinematics is solved, every limit is checked, and
// the speed and acceleration caps of the speed profile come from (speed_profile.hpp).
//
// At each sample the actuator derivatives along the path, q' = dq/ds and q'' = d²q/ds², come from finite
// differences of the inverse kinematics on the grid. With path speed v and tangential acceleration a,
//   q̇ = q'·v,   q̈ = q'·a + q''·v²,
// so the caps are
//   v ≤ margin·q̇_max / |q'_j|,   v ≤ sqrt(α·margin·q̈_max / |q''_j|),   a ≤ (1 − α)·margin·q̈_max / |q'_j|,
// with α = ½ of the acceleration budget reserved for the curvature term. The path's own limits: the
// programmed feed times the override, the path acceleration (also normal: κ·v² ≤ a_path), and the chord error
// between servo periods (textbook eq. 2.3: v ≤ sqrt(8·R·δ)/h, on the tool and on every actuator).
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"
#include "planning/motion_plan.hpp"
#include "planning/speed_profile.hpp"

namespace pkm::planning {

struct SamplingSettings {
  double override_factor = 1.0;
  double actuator_margin = 0.95;
  double spacing = 1.0;            ///< largest sample spacing, path units
  double condition_spacing = 2.0;  ///< conditioning checked at least this often, path units
  double period_s = 0.001;
  double stop_hold_s = 0.0;  ///< rest at every stop so that the jerk filter settles there
  double chord_tolerance_mm =
      1e-3;  ///< allowed deviation between servo periods, on the tool and on actuators
  std::size_t max_samples = 50'000'000;  ///< refuse a path that needs more (PlanOptions::max_samples)
  ProgressSink progress;                 ///< told "planning", the fraction of samples and their line
};

struct SamplingResult {
  PlanStatistics statistics;
};

/// Fills `samples` (s, caps, holds) and `sample_segment`. Errors name the program line and the limit.
Result<SamplingResult> sample_path(const Machine& machine, const program::CanonicalProgram& program,
                                   const path::Path& path, const SamplingSettings& settings,
                                   ProfileSamples& samples, std::vector<int>& sample_segment);

/// The speed cap a segment's programmed feed sets (path units per second): the feed (or rapid) times the
/// override, capped by the machine's rapid, feed or angular speed.
double segment_speed_cap(const path::Segment& segment, const MotionSettings& motion, double override_factor);

/// "X.. Y.. Z.. A.. B.. C.." of a machine pose in program coordinates, for messages.
std::string program_pose_text(const Machine& machine, const Pose& pose);

}  // namespace pkm::planning
