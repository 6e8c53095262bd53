#pragma once
// The HAL files of a LinuxCNC configuration that concern the drives (docs/linuxcnc.md): drives.hal, the
// drives themselves (simulated step or servo drives, with commented examples of real ones at the machine's
// resolution), and execute.hal, pkm's executor pkmexec between LinuxCNC's motion controller and the drives.
//
// Every joint J has two signals the files share: jJ-pos-cmd, the drive's position command (LinuxCNC's
// joint.J.motor-pos-cmd, or with execute.hal the command of whichever of LinuxCNC and pkmexec has the
// drives), and jJ-pos-fb, where the drive is (joint.J.motor-pos-fb).
#include <string>
#include <vector>

#include "pipeline/linuxcnc_config.hpp"

namespace pkm {

struct LinuxcncDrivesHal {
  int joints = 6;
  double step = 0.001;  ///< one drive step in the joints' unit
  bool angles = false;  ///< joints in degrees (angular actuators), else mm
  double speed = 0.0;   ///< the drives' speed limit, joints' unit per second
  double period_s = 0.001;
  LinuxcncDrives kind = LinuxcncDrives::steps;
  bool execute = false;  ///< execute.hal commands the drives (jJ-pos-cmd comes from it)
  std::vector<LinuxcncHomingSwitch> homing_switches;  ///< per joint, when homing on switches
  std::vector<double> home_joints;
};

/// drives.hal.
std::string linuxcnc_drives_hal(const LinuxcncDrivesHal& drives);

/// execute.hal: pkmexec loaded with the machine file at `machine_file`, the hand-over between LinuxCNC's
/// motion controller and pkmexec, and the operator's feed override, feed hold and abort.
std::string linuxcnc_execute_hal(int joints, const std::string& machine_file, int servo_period_ns);

}  // namespace pkm
