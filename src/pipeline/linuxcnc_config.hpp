#pragma once
// A complete simulated LinuxCNC configuration for a machine (docs/linuxcnc.md): an INI file, the HAL file of
// a servo loop whose joints are the machine's actuators, the machine file itself (which pkm's kinematics
// module pkmkins reads when it loads) and an empty tool table, so that `linuxcnc DIR/machine.ini` jogs and
// runs the machine. Joint limits, speeds and accelerations come from the machine file's `limits:`, axis
// speeds from `motion:`, the servo period from `drives:`, and the program origin becomes G54.
//
// LinuxCNC's A B C are G-code's, R = Rz(C)·Ry(B)·Rx(A), whatever the machine file's convention (pkmkins
// converts; docs/part-programs.md, "What A, B and C mean"): the INI's home and axis limits are in them too.
//
// With --execute the configuration also loads pkm's executor (linuxcnc_hal_files.hpp): LinuxCNC homes, jogs
// and runs G-code as usual, and programs that pkm plans run through pkmexec with their exact drive steps.
//
// With LinuxCNC's own genhexkins instead of pkmkins (for comparing the two), the HAL file sets genhexkins'
// joint coordinates from the machine; that needs six strut-length actuators.
#include <string>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm {

/// pkm's module; LinuxCNC's genhexkins for comparison; LinuxCNC's identity kinematics trivkins, whose joints
/// are the controlled coordinates themselves (not the machine: the baseline of the servo-thread time
/// comparison).
enum class LinuxcncKinematics { pkmkins, genhexkins, trivkins };

/// How the joints home: at once where the machine file's home puts them (a simulated machine without
/// switches), or the textbook's search: each strut at speed v1 to its lower boundary switch, back off it at
/// v2 ≪ v1 until it releases (the origin, to within v2·h), then to home. The simulated configuration then has
/// a switch per joint (LinuxCNC's sim_home_switch) where a real machine wires its own.
enum class LinuxcncHoming { at_home, switches };

/// Where each joint's lower boundary switch is, and the speeds of the search (v1) and the latch (v2), in
/// LinuxCNC's joint units: a percent of the range below actuator_min (outside the software stops, as the
/// textbook places the boundary sensors), v1 a quarter of the drive's speed limit, v2 = v1 / 50.
struct LinuxcncHomingSwitch {
  double switch_position = 0.0;
  double search_speed = 0.0;
  double latch_speed = 0.0;
};

/// The drives the configuration simulates (and shows real examples of): step drives, each where it is
/// commanded, or servo drives, a position loop on a motor.
enum class LinuxcncDrives { steps, servo };

struct LinuxcncConfigOptions {
  std::string out_directory;
  LinuxcncKinematics kinematics = LinuxcncKinematics::pkmkins;
  /// LinuxCNC's user interface ([DISPLAY] DISPLAY): a GUI such as axis, or a program run instead (headless).
  std::string display = "axis";
  LinuxcncHoming homing = LinuxcncHoming::at_home;
  LinuxcncDrives drives = LinuxcncDrives::steps;
  /// pkm's executor pkmexec between LinuxCNC's motion controller and the drives (execute.hal): programs
  /// planned by pkm (`pkm linuxcnc stream`) run with their exact drive steps, LinuxCNC homes and jogs in
  /// between.
  bool execute = false;
};

struct LinuxcncConfig {
  std::vector<std::string> files;   ///< written, in DIR
  std::string directory;            ///< DIR, absolute (as pkmkins' machine= argument names it)
  std::string coordinates;          ///< LinuxCNC axis letters of the controlled coordinates, e.g. "XYZABC"
  std::vector<double> home_joints;  ///< joint positions at home, LinuxCNC units (mm, or deg)
  int servo_period_ns = 0;
  std::vector<LinuxcncHomingSwitch> homing_switches;  ///< per joint, with LinuxcncHoming::switches
};

/// Writes the configuration into options.out_directory, all files or none. Fails, naming the machine file
/// key, without actuator limits (LinuxCNC needs joint limits, speeds and accelerations), when home is out of
/// reach or outside the limits, and for genhexkins on a machine it cannot describe.
Result<LinuxcncConfig> write_linuxcnc_config(const Machine& machine, const LinuxcncConfigOptions& options);

/// The genhexkins name, or the pkmkins one, as the CLI spells them.
std::string_view to_string(LinuxcncKinematics kinematics);

}  // namespace pkm
