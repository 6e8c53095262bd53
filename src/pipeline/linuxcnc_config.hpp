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

struct LinuxcncConfigOptions {
  std::string out_directory;
  LinuxcncKinematics kinematics = LinuxcncKinematics::pkmkins;
  /// LinuxCNC's user interface ([DISPLAY] DISPLAY): a GUI such as axis, or a program run instead (headless).
  std::string display = "axis";
};

struct LinuxcncConfig {
  std::vector<std::string> files;   ///< written, in DIR
  std::string directory;            ///< DIR, absolute (as pkmkins' machine= argument names it)
  std::string coordinates;          ///< LinuxCNC axis letters of the controlled coordinates, e.g. "XYZABC"
  std::vector<double> home_joints;  ///< joint positions at home, LinuxCNC units (mm, or deg)
  int servo_period_ns = 0;
};

/// Writes the configuration into options.out_directory, all files or none. Fails, naming the machine file
/// key, without actuator limits (LinuxCNC needs joint limits, speeds and accelerations), when home is out of
/// reach or outside the limits, and for genhexkins on a machine it cannot describe.
Result<LinuxcncConfig> write_linuxcnc_config(const Machine& machine, const LinuxcncConfigOptions& options);

/// The genhexkins name, or the pkmkins one, as the CLI spells them.
std::string_view to_string(LinuxcncKinematics kinematics);

}  // namespace pkm
