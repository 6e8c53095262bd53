#pragma once
// Running the pkm binary from tests: exit code and output of one command line.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
/// A CSV file's header line and its rows split at commas (an empty last cell kept).
struct CsvRows {
  std::string header;
  std::vector<std::vector<std::string>> rows;
};
inline CsvRows read_csv_rows(const std::string& path) {
  std::ifstream in(path);
  CsvRows out;
  std::getline(in, out.header);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream text(line);
    for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    out.rows.push_back(fields);
  }
  return out;
}

inline std::string write_temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_cli_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace pkm::test
