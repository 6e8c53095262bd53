// The progress line of the long commands: the phases in order, the bar, the program line, the ticks written,
// elapsed and left; nothing on stderr where it is not asked for and stderr is not a terminal.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> stderr_lines(const std::string& args) {
  const auto run = test::run_pkm_command(test::pkm_binary_path() + " " + args + " 2>&1 >/dev/null");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  std::vector<std::string> lines;
  std::istringstream text(run.out);
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

std::string plan_args(const std::string& name, const std::string& progress) {
  const fs::path out = fs::temp_directory_path() / ("pkm_progress_cli_" + name);
  fs::remove_all(out);
  return "plan " + test::source_path("examples/programs/pocket.ngc") + " --machine " +
         test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + out.string() + " --report " +
         (out / "report.html").string() + " --progress " + progress;
}

TEST(ProgressCli, AsLinesThePhasesComeInOrderWithLineElapsedAndTheEnd) {
  const std::vector<std::string> lines = stderr_lines(plan_args("always", "always"));
  ASSERT_GE(lines.size(), 2U);
  EXPECT_EQ(lines.front(), "pkm plan: reading the program  0:00 elapsed");
  // Every line names the command and its elapsed time; a fraction comes with its bar; the writing of the
  // outputs, and only it, tells the ticks written ("1 tick", "812 ticks", "48.1 k ticks", "1.2 M ticks").
  const std::regex shape(
      R"(pkm plan: [a-z' ]+(  \[[#.]{20}\] +\d+ %)?(  line \d+)?(  (1 tick|\d+ ticks|\d+\.\d [kM] ticks))?)"
      R"(  \d+:\d\d elapsed(  \d+:\d\d left)?)");
  const std::regex ticks(R"(  (1 tick|[1-9]\d* ticks|\d+\.\d [kM] ticks)  )");
  for (const std::string& line : lines) {
    EXPECT_TRUE(std::regex_match(line, shape)) << line;
    const bool writes = line.find("writing the outputs") != std::string::npos;
    EXPECT_EQ(std::regex_search(line, ticks), writes) << line;
  }
  // The last line is where the command ended: the report, after every tick was written.
  EXPECT_NE(lines.back().find("writing the report"), std::string::npos) << lines.back();
  const std::vector<std::string> order = {
      "reading the program", "building the tool path", "planning",
      "timing the motion",   "writing the outputs",    "writing the report"};
  std::size_t at = 0;
  for (const std::string& line : lines) {
    const std::string phase = line.substr(10, line.find("  ") - 10);
    const auto found = std::find(order.begin() + static_cast<long>(at), order.end(), phase);
    ASSERT_NE(found, order.end()) << "phase out of order or unknown: " << line;
    at = static_cast<std::size_t>(found - order.begin());
  }
}

// Without a report the writing of the outputs is the last phase: the last line, written as the command ends,
// counts every tick of the run (a short and a long count).
TEST(ProgressCli, TheLastLineCountsEveryTickWritten) {
  for (const char* program : {"ch5_line.ngc", "pocket.ngc"}) {
    const fs::path out = fs::temp_directory_path() / ("pkm_progress_cli_ticks_" + std::string(program));
    fs::remove_all(out);
    const std::vector<std::string> lines =
        stderr_lines("plan " + test::source_path(std::string("examples/programs/") + program) +
                     " --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " +
                     out.string() + " --progress always");
    ASSERT_FALSE(lines.empty());
    std::ifstream summary_file(out / "summary.json");
    const long ticks = nlohmann::json::parse(summary_file)["ticks"].get<long>();
    ASSERT_TRUE(ticks > 1 && ticks < 999'950) << ticks;
    const std::string count = ticks < 10'000
                                  ? std::to_string(ticks) + " ticks"
                                  : fmt::format("{:.1f} k ticks", static_cast<double>(ticks) / 1e3);
    EXPECT_EQ(lines.back().rfind("pkm plan: writing the outputs  [####################] 100 %", 0), 0u)
        << lines.back();
    EXPECT_NE(lines.back().find("  " + count + "  "), std::string::npos) << program << ": " << lines.back();
  }
}

TEST(ProgressCli, NeverAndNotATerminalWriteNothing) {
  EXPECT_TRUE(stderr_lines(plan_args("never", "never")).empty());
  EXPECT_TRUE(stderr_lines(plan_args("auto", "auto")).empty());
}

TEST(ProgressCli, ABadModeIsRefused) {
  const auto run = test::run_pkm(plan_args("bad", "sometimes"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--progress"), std::string::npos) << run.out;
}

TEST(ProgressCli, TheServoRunTellsItsPhases) {
  const fs::path out = fs::temp_directory_path() / "pkm_progress_cli_servo";
  fs::remove_all(out);
  const std::string machine = test::source_path("examples/machines/hexapod_ch5.yaml");
  ASSERT_EQ(test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                          machine + " --out " + out.string())
                .exit_code,
            0);
  const std::vector<std::string> lines =
      stderr_lines("servo " + out.string() + " --machine " + machine + " --progress always");
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.front(), "pkm servo: reading the plan  0:00 elapsed");
  EXPECT_NE(lines.back().find("running the servo loops"), std::string::npos) << lines.back();
}

TEST(ProgressCli, StrategiesNameEachCaseWithItsPlansPhases) {
  const fs::path out = fs::temp_directory_path() / "pkm_progress_cli_strategies";
  fs::remove_all(out);
  const std::vector<std::string> lines =
      stderr_lines("strategies --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                   " --load tangential=500 --out " + out.string() + " --progress always");
  std::string all;
  for (const std::string& line : lines) all += line + "\n";
  EXPECT_NE(all.find("pkm strategies: zigzag (1 of 5): "), std::string::npos) << all;
  EXPECT_NE(all.find("(5 of 5): "), std::string::npos) << all;
}

}  // namespace
}  // namespace pkm
