#pragma once
// The execution headroom (execution_headroom.hpp) of a machine file's drives, as both ends of an executed
// program compute it: `pkm linuxcnc stream`, which plans the program within the nominal limits, and pkm's HAL
// component pkmexec, which changes the override no faster than the rates. Also the drives' software stops
// in whole steps.
#include "core/result.hpp"
#include "execution/execution_headroom.hpp"
#include "execution/step_executor.hpp"
#include "machine/machine.hpp"

namespace pkm::execution {

/// The largest feed override an executed program allows (LinuxCNC's usual MAX_FEED_OVERRIDE), and the share
/// of the acceleration its motion uses (the rest is for changing the override).
constexpr double kExecutionMaxOverride = 1.2;
constexpr double kExecutionMotionShare = 0.5;

/// In the actuators' units (mm/s and mm/s², or rad/s and rad/s²); errors name the machine file's keys.
Result<ExecutionHeadroom> machine_headroom(const Machine& machine, double period_s);

/// The drive resolution in the actuators' internal unit (mm, or rad for angular actuators) from `step`, given
/// as the machine file's drives.step (mm, or deg).
double step_in_actuator_units(const Machine& machine, double step);

/// The executor's settings for the machine's drives at `step` (machine file units) and `period_s`.
Result<ExecutorSettings> executor_settings(const Machine& machine, double step, double period_s);

}  // namespace pkm::execution
