// pkm plan's memory does not grow with the program: the whole command (reading, planning, the ticks and
// ticks.h5) on a program and on one ten times as long, its peak resident memory (max RSS, from the kernel)
// within 10 % of the shorter run's.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

struct Measured {
  int exit_code = -1;
  long max_rss_kb = 0;
};

/// Runs `pkm plan` in a child process of its own and reads its peak memory from wait4.
Measured plan_and_measure(const std::string& program, const std::string& out_dir) {
  const std::string binary = test::pkm_binary_path();
  const std::string machine = test::source_path("examples/machines/hexapod_ch5.yaml");
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(binary.c_str(), binary.c_str(), "plan", "--machine", machine.c_str(), program.c_str(), "--out",
            out_dir.c_str(), "--max-ticks", "1000000000", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  Measured measured;
  int status = 0;
  rusage usage{};
  if (::wait4(child, &status, 0, &usage) == child && WIFEXITED(status)) {
    measured.exit_code = WEXITSTATUS(status);
    measured.max_rss_kb = usage.ru_maxrss;
  }
  return measured;
}

std::string long_program(int lines) {
  const fs::path path = fs::temp_directory_path() /
                        ("pkm_memory_" + std::to_string(::getpid()) + "_" + std::to_string(lines) + ".ngc");
  const std::string command = "/usr/bin/python3 " + test::source_path("scripts/gen-long-program.py") + " " +
                              path.string() + " " + std::to_string(lines);
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return path.string();
}

TEST(PlanMemory, PeakMemoryOfTenTimesTheProgramStaysWithinTenPercent) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_memory_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string shorter = long_program(4000);
  const std::string longer = long_program(40000);
  const Measured small = plan_and_measure(shorter, (dir / "short").string());
  const Measured large = plan_and_measure(longer, (dir / "long").string());
  ASSERT_EQ(small.exit_code, 0);
  ASSERT_EQ(large.exit_code, 0);
  EXPECT_GT(fs::file_size(dir / "long" / "ticks.h5"), 5 * fs::file_size(dir / "short" / "ticks.h5"));
  EXPECT_LE(large.max_rss_kb, small.max_rss_kb * 11 / 10)
      << "max RSS " << small.max_rss_kb << " kB for 4000 lines, " << large.max_rss_kb << " kB for 40000";
  fs::remove_all(dir);
  fs::remove(shorter);
  fs::remove(longer);
}

}  // namespace
}  // namespace pkm
