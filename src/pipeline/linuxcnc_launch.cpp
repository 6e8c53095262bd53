#include "pipeline/linuxcnc_launch.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <filesystem>

namespace pkm {

std::string linuxcnc_start_command(const std::string& directory, bool as_root) {
  const std::string ini = (std::filesystem::path(directory) / "machine.ini").string();
  if (!as_root) return "linuxcnc " + ini;
  return fmt::format("RTAPI_UID=$(id -u nobody) RTAPI_FIFO_PATH={} linuxcnc {}", kLinuxcncRootFifoPath, ini);
}

bool linuxcnc_display_is_headless(const std::string& display) {
  // linuxcncrsh serves LinuxCNC's text protocol on a TCP port; halui alone has no display of its own.
  return display == "linuxcncrsh" || display.ends_with("headless_run.py");
}

namespace {

// The first folder from the root down to `directory` that other users cannot enter (or read, for the
// directory itself), or empty.
std::string first_closed_folder(const std::filesystem::path& directory) {
  std::filesystem::path folder;
  for (const auto& part : std::filesystem::absolute(directory).lexically_normal()) {
    folder /= part;
    struct stat status {};
    if (::stat(folder.c_str(), &status) != 0) break;  // not made yet: pkm makes it open to read
    const bool last = folder == std::filesystem::absolute(directory).lexically_normal();
    const mode_t needed = last ? (S_IROTH | S_IXOTH) : S_IXOTH;
    if ((status.st_mode & needed) != needed) return folder.string();
  }
  return {};
}

std::string folder_name(const std::string& directory) {
  std::filesystem::path path = std::filesystem::path(directory).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  return path.filename().string();
}

}  // namespace

std::vector<std::string> linuxcnc_start_problems(const std::string& directory, const std::string& display,
                                                 bool as_root, bool has_x_display) {
  std::vector<std::string> problems;
  if (!has_x_display && !linuxcnc_display_is_headless(display)) {
    problems.push_back(fmt::format(
        "the display {} needs an X display and there is none: write the configuration with --display "
        "linuxcncrsh (LinuxCNC's text interface, TCP port 5007) or --display "
        "/path/to/pkm/linuxcnc/headless_run.py (runs one program and exits: docs/linuxcnc.md)",
        display));
  }
  if (as_root) {
    if (const std::string closed = first_closed_folder(directory); !closed.empty()) {
      problems.push_back(
          fmt::format("as root, LinuxCNC's rtapi_app reads machine.yaml as another user (RTAPI_UID), who "
                      "cannot enter {}: "
                      "write the configuration where every user can read it, e.g. --out /tmp/{}",
                      closed, folder_name(directory)));
    }
  }
  return problems;
}

}  // namespace pkm
