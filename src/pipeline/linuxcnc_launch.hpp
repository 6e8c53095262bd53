#pragma once
// How to start LinuxCNC on a configuration written by `pkm linuxcnc config` (docs/linuxcnc.md, "Running it
// as root or without a display"). LinuxCNC's real-time process rtapi_app refuses to run as root unless told
// which user to run as (RTAPI_UID), and it then reads the configuration and writes its socket
// (RTAPI_FIFO_PATH; by default under $HOME, which that user cannot write) as that user; its default display,
// AXIS, needs X.
#include <string>
#include <vector>

namespace pkm {

/// Where rtapi_app puts its socket when LinuxCNC runs as root: a file in /tmp, which every user may create.
inline constexpr const char* kLinuxcncRootFifoPath = "/tmp/linuxcnc-rtapi.fifo";

/// The shell command that starts LinuxCNC on DIRECTORY/machine.ini; as root with the environment rtapi_app
/// needs, e.g. "RTAPI_UID=$(id -u nobody) RTAPI_FIFO_PATH=/tmp/linuxcnc-rtapi.fifo linuxcnc DIR/machine.ini".
std::string linuxcnc_start_command(const std::string& directory, bool as_root);

/// What stops the configuration from running as written here, one sentence each with what to do: a GUI
/// display without an X display, and (as root) a folder the real-time user cannot read.
std::vector<std::string> linuxcnc_start_problems(const std::string& directory, const std::string& display,
                                                 bool as_root, bool has_x_display);

/// Displays that need no X display: LinuxCNC's text interface, and pkm's one-program runner (a path).
bool linuxcnc_display_is_headless(const std::string& display);

}  // namespace pkm
