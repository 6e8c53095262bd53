// pkm plan from the command line: the output files (ticks.h5 by default, the CSV tables with --tables csv),
// the summary, and failures that leave no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_plan_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

int count_lines(const fs::path& file) {
  std::ifstream in(file);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

TEST(PlanCli, WritesActuatorsPathAndSummary) {
  const std::string out = fresh_dir("circle");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                     test::source_path("examples/machines/hexapod_ch5.yaml") +
                                     " --rate 500 --tables csv --out " + out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  for (const char* key : {"duration_s", "max_actuator_speed_mm_s", "max_actuator_accel_mm_s2",
                          "max_path_error_mm", "blocks", "ticks"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_GT(summary["duration_s"].get<double>(), 0.0);
  EXPECT_LE(summary["max_actuator_speed_mm_s"].get<double>(), 100.0);
  EXPECT_LE(summary["max_actuator_accel_mm_s2"].get<double>(), 2000.0);
  EXPECT_LT(summary["max_path_error_mm"].get<double>(), 1e-3);
  EXPECT_DOUBLE_EQ(summary["rate_hz"].get<double>(), 500.0);
  // One row per tick plus the header, in both CSV files; the file summary equals the printed one.
  const long ticks = summary["ticks"].get<long>();
  EXPECT_EQ(count_lines(fs::path(out) / "actuators.csv"), ticks + 1);
  EXPECT_EQ(count_lines(fs::path(out) / "path.csv"), ticks + 1);
  std::ifstream file(fs::path(out) / "summary.json");
  const auto written = nlohmann::json::parse(file);
  EXPECT_EQ(written["ticks"], summary["ticks"]);
  std::ifstream actuators(fs::path(out) / "actuators.csv");
  std::string header;
  std::getline(actuators, header);
  EXPECT_EQ(header, "time_s,q1_mm,q2_mm,q3_mm,q4_mm,q5_mm,q6_mm");
}

TEST(PlanCli, ByDefaultTheTablesAreTicksH5) {
  const std::string out = fresh_dir("default");
  const auto run =
      test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                        test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + out,
                    false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_TRUE(fs::exists(fs::path(out) / "ticks.h5"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "summary.json"));
  for (const char* name : {"actuators.csv", "path.csv"})
    EXPECT_FALSE(fs::exists(fs::path(out) / name)) << name;
  EXPECT_NE(run.out.find(out + "/ticks.h5 (actuators, path), summary.json"), std::string::npos) << run.out;
}

TEST(PlanCli, ALimitViolationNamesTheLineAndWritesNothing) {
  const std::string out = fresh_dir("violation");
  const std::string program =
      test::write_temp_file("plan_climb.ngc", "G21 G90\nG0 X0 Y0 Z0\nG1 Z500 F600\nM2\n");
  const auto run =
      test::run_pkm("plan " + program + " --machine " +
                    test::source_path("examples/machines/hexapod_ch5.yaml") + " --tables csv --out " + out);
  EXPECT_EQ(run.exit_code, 3) << run.out;
  EXPECT_NE(run.out.find("plan_climb.ngc:3:"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("actuator_max"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "actuators.csv"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));
}

TEST(PlanCli, BadProgramAndBadOptionsExitWithTwo) {
  const std::string out = fresh_dir("bad");
  const std::string program = test::write_temp_file("plan_bad.ngc", "G1 X1 F100\nG2 X5\n");
  const auto run = test::run_pkm("plan " + program + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + out);
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("plan_bad.ngc:2"), std::string::npos) << run.out;
  const auto override_run = test::run_pkm(
      "plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
      test::source_path("examples/machines/hexapod_ch5.yaml") + " --override 250 --tables csv --out " + out);
  EXPECT_EQ(override_run.exit_code, 2) << override_run.out;
  EXPECT_NE(override_run.out.find("override"), std::string::npos);
  EXPECT_FALSE(fs::exists(fs::path(out) / "path.csv"));
}

}  // namespace
}  // namespace pkm
