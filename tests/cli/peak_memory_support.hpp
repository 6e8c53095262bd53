#pragma once
// A pkm command run in a child process of its own, its peak resident memory (max RSS) read from the kernel
// (wait4), and the long generated programs the memory tests run it on.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"

namespace pkm::test {

struct PeakMemory {
  int exit_code = -1;
  long max_rss_kb = 0;
};

/// `pkm ARGS…` with its output to /dev/null.
inline PeakMemory run_pkm_measuring_memory(const std::vector<std::string>& args) {
  const std::string binary = pkm_binary_path();
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(binary.c_str()));
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  PeakMemory measured;
  int status = 0;
  rusage usage{};
  if (::wait4(child, &status, 0, &usage) == child && WIFEXITED(status)) {
    measured.exit_code = WEXITSTATUS(status);
    measured.max_rss_kb = usage.ru_maxrss;
  }
  return measured;
}

/// scripts/gen-long-program.py's CAM-like program of `lines` lines, in the temporary folder.
inline std::string long_program(int lines) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("pkm_memory_" + std::to_string(::getpid()) + "_" + std::to_string(lines) + ".ngc");
  const std::string command = "/usr/bin/python3 " + source_path("scripts/gen-long-program.py") + " " +
                              path.string() + " " + std::to_string(lines);
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return path.string();
}

}  // namespace pkm::test
