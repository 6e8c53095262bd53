// pkm interpret: the JSON moves of a part program, the readable table, and errors with line and column.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"
#include "source_paths.hpp"

namespace {

using pkm::test::CliRun;

CliRun interpret_cli_run(const std::string& args, bool with_stderr = true) {
  return pkm::test::run_pkm(args, with_stderr);
}

std::string interpret_cli_write_temp(const std::string& name, const std::string& text) {
  return pkm::test::write_temp_file("interpret_" + name, text);
}

TEST(InterpretCli, JsonListsEveryMoveWithItsFields) {
  const std::string program = interpret_cli_write_temp("ok.ngc",
                                                       "G21 G90 G17\n"
                                                       "G0 X10 Y0 Z5\n"
                                                       "G1 Z0 F300\n"
                                                       "G3 X0 Y10 I-10 J0 A15\n"
                                                       "G4 P0.5\n"
                                                       "M2\n");
  const CliRun r = interpret_cli_run("interpret " + program + " --json", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 4u);
  EXPECT_EQ(j[0]["kind"], "rapid");
  EXPECT_EQ(j[0]["line"], 2);
  EXPECT_EQ(j[0]["end"].size(), 6u);
  EXPECT_EQ(j[0]["feed_mm_min"], 0.0);
  EXPECT_FALSE(j[0].contains("center"));
  EXPECT_EQ(j[1]["kind"], "line");
  EXPECT_DOUBLE_EQ(j[1]["feed_mm_min"].get<double>(), 300.0);
  const auto& arc = j[2];
  EXPECT_EQ(arc["kind"], "arc");
  EXPECT_EQ(arc["line"], 4);
  EXPECT_DOUBLE_EQ(arc["end"][0].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(arc["end"][1].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(arc["end"][3].get<double>(), 15.0);
  ASSERT_EQ(arc["center"].size(), 3u);
  EXPECT_DOUBLE_EQ(arc["center"][0].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(arc["normal"][2].get<double>(), 1.0);
  EXPECT_EQ(arc["turns"], 1);
  EXPECT_EQ(j[3]["kind"], "dwell");
  EXPECT_DOUBLE_EQ(j[3]["dwell_s"].get<double>(), 0.5);
}

TEST(InterpretCli, TableIsReadable) {
  const std::string program = interpret_cli_write_temp("table.ngc", "G21 F100\nG1 X1\nM3 S1000\nM2\n");
  const CliRun r = interpret_cli_run("interpret " + program);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("line"), std::string::npos);
  EXPECT_NE(r.out.find("M3 S1000"), std::string::npos);
  EXPECT_NE(r.out.find("1 moves"), std::string::npos);
}

TEST(InterpretCli, BadProgramExitsTwoWithLineAndColumn) {
  const std::string program = interpret_cli_write_temp("bad.ngc", "G21 F100\nG1 X1\nG0 G41 X2\n");
  const CliRun r = interpret_cli_run("interpret " + program);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("pkm interpret: error: " + program + ":3:4: unsupported G-code G41"),
            std::string::npos)
      << r.out;
}

TEST(InterpretCli, MissingProgramExitsTwoNamingIt) {
  const CliRun r = interpret_cli_run("interpret /nonexistent/pkm/none.ngc");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("/nonexistent/pkm/none.ngc"), std::string::npos) << r.out;
}

TEST(InterpretCli, ToolTableAndMachineOptions) {
  const std::string table = interpret_cli_write_temp("tools.tbl", "T1 P1 Z25 D6\n");
  const std::string program = interpret_cli_write_temp("tool.ngc", "G21 F100\nG0 Z10\nG43 H1\nG1 X1\nM2\n");
  const std::string machine = pkm::test::source_path("examples/machines/hexapod_ch5.yaml");
  const CliRun r = interpret_cli_run(
      "interpret " + program + " --tool-table " + table + " --machine " + machine + " --json", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_DOUBLE_EQ(j[1]["end"][2].get<double>(), 10.0 - 25.0);
  const CliRun bad_machine = interpret_cli_run("interpret " + program + " --machine /nonexistent/pkm/m.yaml");
  EXPECT_EQ(bad_machine.exit_code, 2) << bad_machine.out;
  const CliRun no_table = interpret_cli_run("interpret " + program);
  EXPECT_EQ(no_table.exit_code, 2) << no_table.out;
  EXPECT_NE(no_table.out.find(":3:5: G43 for"), std::string::npos) << no_table.out;
}

}  // namespace
