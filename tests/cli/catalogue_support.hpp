#pragma once
// What the bad-input catalogues share (bad_input_catalogue_test.cpp, bad_input_campaign_test.cpp): running
// the real pkm binary with its stderr kept apart, a snapshot of an output folder to compare before and after
// a failed run, the sentinel plan run a failure must leave alone, and the {t} {m} {line} substitutions of a
// case's arguments.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "source_paths.hpp"

namespace pkm::test {

inline std::string catalogue_read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct CatalogueRun {
  int exit_code;
  bool signalled;
  std::string out;
  std::string err;
  double seconds;
};

/// pkm with `args`, stdout captured, stderr into `stderr_file` and read back.
inline CatalogueRun catalogue_run_pkm(const std::string& args, const std::filesystem::path& stderr_file) {
  const std::string command = pkm_binary_path() + " " + args + " 2>" + stderr_file.string();
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> buffer{};
  std::size_t got = 0;
  while (pipe && (got = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), got);
  const int status = pipe ? pclose(pipe) : -1;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The shell reports a signal as 128 + n; either way it is a crash.
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return {code, code >= 128, out, catalogue_read(stderr_file), seconds};
}

using CatalogueSnapshot = std::map<std::string, std::string>;  // relative path -> content ("<dir>")

/// Every file and folder below `root` (or the file `root` itself) with its content.
inline CatalogueSnapshot catalogue_snapshot(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  CatalogueSnapshot snapshot;
  if (!fs::exists(root)) return snapshot;
  if (!fs::is_directory(root)) return {{"", catalogue_read(root)}};
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    snapshot[fs::relative(entry.path(), root).string()] =
        entry.is_directory() ? std::string("<dir>") : catalogue_read(entry.path());
  }
  return snapshot;
}

inline std::string catalogue_ch5() {
  return source_path("examples/machines/hexapod_ch5.yaml");
}
inline std::string catalogue_line() {
  return source_path("examples/programs/ch5_line.ngc");
}

/// A complete plan run in t/run: what a failed command that reads or writes there must leave alone.
inline void catalogue_plan_sentinel(const std::filesystem::path& t) {
  const auto run = catalogue_run_pkm("plan " + catalogue_line() + " --machine " + catalogue_ch5() +
                                         " --no-path-error --out " + (t / "run").string(),
                                     t / "sentinel.err");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(std::filesystem::exists(t / "run" / "summary.json"));
}

/// A case's arguments with {t} (its temporary folder), {m} (the ch5 hexapod) and {line} (the ch5 test line).
inline std::string catalogue_expand(std::string text, const std::filesystem::path& t) {
  const std::pair<std::string, std::string> names[] = {
      {"{t}", t.string()}, {"{m}", catalogue_ch5()}, {"{line}", catalogue_line()}};
  for (const auto& [key, value] : names) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  }
  return text;
}

}  // namespace pkm::test
