// pkm servo on a planned run of the shipped ch5 hexapod (its servo: section): the printed summary and its
// JSON, the files it writes beside the plan; a machine without a servo: section, a directory that is not a
// plan and a damaged actuators.csv exit 2 naming what is wrong and write nothing; a plan whose tables are
// ticks.h5 gives the servo run of its CSV tables.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string servo_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

// The ch5 line planned into a fresh directory, its tables as CSV files (or `tables`).
std::string servo_cli_plan(const std::string& name, const std::string& tables = "csv") {
  const fs::path dir = fs::temp_directory_path() / ("pkm_servo_cli_" + name);
  fs::remove_all(dir);
  const auto planned = test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") +
                                     " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --tables " +
                                     tables + " --out " + (dir / "plan").string());
  EXPECT_EQ(planned.exit_code, 0) << planned.out;
  return (dir / "plan").string();
}

TEST(ServoCli, PrintsTheSummaryAndWritesTheFilesBesideThePlan) {
  const std::string plan = servo_cli_plan("summary");
  const auto run = test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("contour error   max"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("drive 6"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("technical_optimum"), std::string::npos) << run.out;
  for (const char* file : {"servo.csv", "servo_bode.csv", "servo_summary.json"})
    EXPECT_TRUE(fs::exists(fs::path(plan) / file)) << file;

  const auto json = test::run_pkm(
      "servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --json --decoupled", false);
  ASSERT_EQ(json.exit_code, 0) << json.out;
  const nlohmann::json summary = nlohmann::json::parse(json.out);
  EXPECT_EQ(summary["kind"], "servo");
  EXPECT_EQ(summary["coupled"], false);
  ASSERT_EQ(summary["drives"].size(), 6u);
  for (const auto& drive : summary["drives"]) {
    // The shipped drives are tuned to the technical optimum: 4.3 % and 8.1 % overshoot, continuous.
    EXPECT_NEAR(drive["speed_loop"]["continuous"]["overshoot_pct"].get<double>(), 4.32, 0.05);
    EXPECT_NEAR(drive["position_loop"]["continuous"]["overshoot_pct"].get<double>(), 8.15, 0.05);
    EXPECT_GT(drive["max_following_error"].get<double>(), 0.0);
  }
  EXPECT_GT(summary["max_contour_error_mm"].get<double>(), 0.0);
}

TEST(ServoCli, RefusesAMachineWithoutServoAPlanlessDirectoryAndADamagedRunWritingNothing) {
  const std::string plan = servo_cli_plan("bad");
  const auto no_servo =
      test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch3.yaml"));
  EXPECT_EQ(no_servo.exit_code, 2) << no_servo.out;
  EXPECT_NE(no_servo.out.find("no servo: section"), std::string::npos) << no_servo.out;

  const fs::path empty = fs::path(plan).parent_path() / "empty";
  fs::create_directories(empty);
  const auto planless =
      test::run_pkm("servo " + empty.string() + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  EXPECT_EQ(planless.exit_code, 2) << planless.out;
  EXPECT_NE(planless.out.find("actuators.csv"), std::string::npos) << planless.out;
  EXPECT_TRUE(fs::is_empty(empty));

  // A row of actuators.csv with a word where a length should be: its file and line.
  const fs::path actuators = fs::path(plan) / "actuators.csv";
  std::ifstream in(actuators);
  std::string text, line;
  for (int row = 1; std::getline(in, line); ++row)
    text += (row == 40 ? "0.039000,abc" + line.substr(line.find(',', line.find(',') + 1)) : line) + "\n";
  in.close();
  std::ofstream(actuators) << text;
  const auto damaged = test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  EXPECT_EQ(damaged.exit_code, 2) << damaged.out;
  EXPECT_NE(damaged.out.find("actuators.csv:40"), std::string::npos) << damaged.out;
  EXPECT_FALSE(fs::exists(fs::path(plan) / "servo.csv"));
}

TEST(ServoCli, APlanOfHdf5TablesGivesTheServoRunOfItsCsvTables) {
  nlohmann::json summaries[2];
  const char* forms[2] = {"csv", "hdf5"};
  for (int k = 0; k < 2; ++k) {
    const std::string plan = servo_cli_plan(std::string("forms_") + forms[k], forms[k]);
    EXPECT_EQ(fs::exists(fs::path(plan) / "ticks.h5"), k == 1);
    const auto run = test::run_pkm(
        "servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --json", false);
    ASSERT_EQ(run.exit_code, 0) << run.out;
    summaries[k] = nlohmann::json::parse(run.out);
  }
  EXPECT_EQ(summaries[1]["ticks"], summaries[0]["ticks"]);
  EXPECT_GT(summaries[0]["ticks"].get<long>(), 100);
  // The set points differ by the tables' rounding (1e-6 mm): the loops' errors by as little.
  for (const char* key : {"max_contour_error_mm", "rms_contour_error_mm"}) {
    const double csv = summaries[0][key].get<double>(), hdf5 = summaries[1][key].get<double>();
    EXPECT_GT(csv, 0.0) << key;
    EXPECT_NEAR(hdf5, csv, 1e-3 * csv + 1e-6) << key;
  }
  EXPECT_EQ(summaries[1]["max_contour_line"], summaries[0]["max_contour_line"]);
}

}  // namespace
}  // namespace pkm
