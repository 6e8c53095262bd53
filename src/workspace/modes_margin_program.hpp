#pragma once
// The assembly-mode margin along a planned program (`pkm modes-margin`): the planned motion is
// sampled evenly in time, at the servo ticks nearest to k·T/(samples + 1) for k = 0 … samples + 1 (the start,
// `samples` poses between and the end; fewer where the run has fewer ticks), each with the program line it
// comes from; at every sample the margin (modes_margin.hpp) and the other assembly modes (other_modes.hpp)
// are computed, and the summary gives the smallest margin with its line, time and pose, the nearest other
// mode with its line, and the range of the real mode counts.
#include <optional>
#include <vector>

#include "planning/motion_plan.hpp"
#include "workspace/modes_margin.hpp"
#include "workspace/other_modes.hpp"

namespace pkm::workspace {

struct ProgramModesMarginOptions {
  int samples = 200;  ///< poses between the start and the end (≥ 1)
  ModesMarginOptions margin;
  int threads = 0;  ///< worker threads for the samples (0: every core); the result does not depend on it
};

struct ModesMarginSample {
  long tick = 0;  ///< servo tick of the planned run
  double time_s = 0.0;
  int line = 0;               ///< program line of the move the pose is on
  AssemblyModeMargin margin;  ///< its pose and actuators are the sample's (completed) pose and IK
  OtherAssemblyModes modes;
};

struct ModesMarginSummary {
  int samples = 0;
  int margins_found = 0;    ///< samples with a singular configuration found
  int margins_bounded = 0;  ///< of those, where no search converged: the margin is a plain upper bound
  std::optional<std::size_t> min_margin;          ///< the sample with the smallest margin (among those found)
  std::optional<std::size_t> max_margin;          ///< and the largest
  int modes_enumerated = 0;                       ///< samples where forward_all answered
  std::optional<std::size_t> nearest_other_mode;  ///< the sample whose other mode is nearest (|Δp| + L·|Δθ|)
  int min_real_modes = -1;                        ///< over the enumerated samples (−1: none enumerated)
  int max_real_modes = -1;
  std::string modes_note;  ///< why modes were not enumerated (the first sample's reason), if any were not
};

struct ProgramModesMargin {
  std::string program_source;
  double duration_s = 0.0;
  std::vector<ModesMarginSample> samples;
  ModesMarginSummary summary;
};

/// The margin along `plan` (planned on `machine`). Fails for samples < 1 (bad_input), where the planned run
/// leaves the workspace or the actuators' range (naming the program line), and for a mechanism without a
/// square actuator Jacobian (unsupported).
Result<ProgramModesMargin> modes_margin_along_plan(const Machine& machine, const planning::MotionPlan& plan,
                                                   const ProgramModesMarginOptions& options = {});

/// The summary of `samples` (modes_margin_along_plan fills it; exposed for tests).
ModesMarginSummary summarise_modes_margin(const std::vector<ModesMarginSample>& samples);

}  // namespace pkm::workspace
