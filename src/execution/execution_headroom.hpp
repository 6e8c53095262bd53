#pragma once
// How much of the drives' limits the planned (nominal) motion may use so that its execution at any feed
// override up to K_max, with a feed hold or an abort at any period, stays within every limit; and how fast
// the override factor K may then change (override_law.hpp).
//
// With the nominal motion within speed v_n, acceleration a_n and jerk j_n, the executed motion has
//   |q̇| ≤ v_n·K,   |q̈| ≤ a_n·K² + v_n·|K̇|,   |q⃛| ≤ j_n·K³ + 3·a_n·K·|K̇| + v_n·|K̈|,
// so with K ≤ K_max, a share η of the acceleration and jerk for the motion and the rest for changing K:
//   v_n = v/K_max,  a_n = η·a/K_max²,  j_n = η·j/K_max³,
//   |K̇| ≤ (1 − η)·a/v_n,   |K̈| ≤ ((1 − η)·j − 3·a_n·K_max·|K̇|_max)/v_n.
// Without a jerk limit K̈ takes |K̇|_max in kRateRiseS. The executor's window must hold the periods K needs
// to stop from K_max (StepExecutor::kWindow); rates that do not fit are refused.
#include <optional>

#include "core/result.hpp"
#include "execution/override_law.hpp"

namespace pkm::execution {

struct DriveLimits {
  double speed = 0.0;  ///< per second, in the drives' unit (mm or rad; or steps)
  double accel = 0.0;
  std::optional<double> jerk;
};

struct ExecutionHeadroom {
  DriveLimits nominal;  ///< what the planned motion may use
  OverrideRates rates;  ///< how fast K may change
  double max_override = 1.2;
  double motion_share = 0.5;  ///< η
};

/// Seconds in which K̇ reaches its largest value when the drives have no jerk limit.
constexpr double kRateRiseS = 0.02;

/// The headroom for drives with `limits`, overrides up to `max_override` (≥ 1) and the motion's share η of
/// acceleration and jerk (0 < η < 1), at servo period `period_s`. Errors name what does not fit.
Result<ExecutionHeadroom> execution_headroom(const DriveLimits& limits, double max_override,
                                             double motion_share, double period_s);

}  // namespace pkm::execution
