// How pkm linuxcnc config says to start LinuxCNC (pipeline/linuxcnc_launch.hpp): as root with the user and
// the socket rtapi_app needs, and what would stop the configuration here (no X display for AXIS, a folder the
// real-time user cannot enter).
#include "pipeline/linuxcnc_launch.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

namespace pkm {
namespace {

namespace fs = std::filesystem;

TEST(LinuxcncLaunch, StartCommandAsRootNamesTheUserAndTheSocket) {
  EXPECT_EQ(linuxcnc_start_command("/tmp/ch5", false), "linuxcnc /tmp/ch5/machine.ini");
  EXPECT_EQ(
      linuxcnc_start_command("/tmp/ch5", true),
      "RTAPI_UID=$(id -u nobody) RTAPI_FIFO_PATH=/tmp/linuxcnc-rtapi.fifo linuxcnc /tmp/ch5/machine.ini");
}

TEST(LinuxcncLaunch, AWindowWithoutAnXDisplayIsAProblemAHeadlessDisplayIsNot) {
  const auto problems = linuxcnc_start_problems("/tmp/ch5", "axis", false, false);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("--display linuxcncrsh"), std::string::npos) << problems[0];
  EXPECT_TRUE(linuxcnc_start_problems("/tmp/ch5", "axis", false, true).empty());
  EXPECT_TRUE(linuxcnc_start_problems("/tmp/ch5", "linuxcncrsh", false, false).empty());
  EXPECT_TRUE(linuxcnc_start_problems("/tmp/ch5", "/src/pkm/linuxcnc/headless_run.py", false, false).empty());
}

TEST(LinuxcncLaunch, AsRootAFolderClosedToOtherUsersIsNamed) {
  const fs::path closed = fs::temp_directory_path() / "pkm_linuxcnc_launch_test_closed";
  fs::remove_all(closed);
  fs::create_directories(closed / "config");
  ::chmod(closed.c_str(), 0700);
  const auto problems = linuxcnc_start_problems((closed / "config").string(), "linuxcncrsh", true, false);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find(closed.string() + ":"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("--out /tmp/config"), std::string::npos) << problems[0];
  // Not as root, rtapi_app reads as the user who runs it: no problem.
  EXPECT_TRUE(linuxcnc_start_problems((closed / "config").string(), "linuxcncrsh", false, false).empty());
  ::chmod(closed.c_str(), 0755);
  EXPECT_TRUE(linuxcnc_start_problems((closed / "config").string(), "linuxcncrsh", true, false).empty());
  fs::remove_all(closed);
}

}  // namespace
}  // namespace pkm
