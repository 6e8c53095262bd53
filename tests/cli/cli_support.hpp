#pragma once
// Running the pkm binary from tests: exit code and output of one command line.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "source_paths.hpp"

namespace pkm::test {

struct CliRun {
  int exit_code;
  std::string out;  ///< stdout, and stderr too unless asked otherwise
};

inline CliRun run_pkm_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> buffer{};
  while (pipe && fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline CliRun run_pkm(const std::string& args, bool with_stderr = true) {
  return run_pkm_command(pkm_binary_path() + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null"));
}

/// The same, run from `directory` (relative paths in `args` are taken from there).
inline CliRun run_pkm_in(const std::string& directory, const std::string& args) {
  return run_pkm_command("cd '" + directory + "' && " + pkm_binary_path() + " " + args + " 2>&1");
}

/// Writes `text` to a file in the temporary directory and returns its path.
inline std::string write_temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_cli_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace pkm::test
