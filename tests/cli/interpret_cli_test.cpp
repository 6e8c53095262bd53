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
  const auto document = nlohmann::json::parse(r.out);
  ASSERT_TRUE(document.is_object());
  EXPECT_EQ(document["source"], program);
  ASSERT_EQ(document["files"].size(), 1u);
  EXPECT_EQ(document["files"][0], program);
  EXPECT_TRUE(document["events"].is_array());
  EXPECT_EQ(document["end_line"], 6);
  const auto& j = document["moves"];
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 4u);
  EXPECT_EQ(j[0]["kind"], "rapid");
  EXPECT_EQ(j[0]["line"], 2);
  EXPECT_EQ(j[0]["end"].size(), 6u);
  EXPECT_EQ(j[0]["program_end"], j[0]["end"]);  // no offsets: the program's coordinates are the work's
  EXPECT_EQ(j[0]["file"], 0);
  EXPECT_TRUE(j[0]["source_line"].is_number_integer());  // the interpreter's (its own tests check the value)
  EXPECT_EQ(j[0]["plane"], "xy");
  EXPECT_EQ(j[0]["tool_length_mm"], 0.0);
  EXPECT_EQ(j[0]["frame"]["system"], 1);
  EXPECT_EQ(j[0]["frame"]["g5x"].size(), 6u);
  EXPECT_EQ(j[0]["frame"]["g92"].size(), 6u);
  EXPECT_EQ(j[0]["frame"]["xy_rotation_deg"], 0.0);
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
  EXPECT_EQ(arc["program_center"], arc["center"]);
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
  const std::string program = interpret_cli_write_temp("bad.ngc", "G21 F100\nG1 X1\nG0 G33 X2\n");
  const CliRun r = interpret_cli_run("interpret " + program);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("pkm interpret: error: " + program + ":3:4: unsupported G-code G33"),
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
  const auto j = nlohmann::json::parse(r.out)["moves"];
  ASSERT_EQ(j.size(), 2u);
  EXPECT_DOUBLE_EQ(j[1]["end"][2].get<double>(), 10.0 - 25.0);
  const CliRun bad_machine = interpret_cli_run("interpret " + program + " --machine /nonexistent/pkm/m.yaml");
  EXPECT_EQ(bad_machine.exit_code, 2) << bad_machine.out;
  // Without a table tools have zero length, as in rs274, and the note says so.
  const CliRun no_table = interpret_cli_run("interpret " + program);
  EXPECT_EQ(no_table.exit_code, 0) << no_table.out;
  EXPECT_NE(no_table.out.find("note: " + program + ":3: G43 for tool 1 without a tool table"),
            std::string::npos)
      << no_table.out;
}

TEST(InterpretCli, JsonListsEventsWithTheirSource) {
  const std::string program = interpret_cli_write_temp("events.ngc", "G21 F100\nM3 S1000\nG1 X1\nM5\nM2\n");
  const CliRun r = interpret_cli_run("interpret " + program + " --json", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto events = nlohmann::json::parse(r.out)["events"];
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events[0]["line"], 2);
  EXPECT_EQ(events[0]["file"], 0);
  EXPECT_TRUE(events[0]["source_line"].is_number_integer());
  EXPECT_NE(events[0]["what"].get<std::string>().find("M3"), std::string::npos);
}

TEST(InterpretCli, EmptyProgramIsAnEmptyDocument) {
  const std::string program = interpret_cli_write_temp("empty.ngc", "M2\n");
  const CliRun r = interpret_cli_run("interpret " + program + " --json", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto document = nlohmann::json::parse(r.out);
  EXPECT_TRUE(document["moves"].empty());
  EXPECT_TRUE(document["events"].is_array());
}

TEST(InterpretCli, CountPrintsOnlyTheSummary) {
  const std::string program = interpret_cli_write_temp("count.ngc", "G21 F100\nG1 X1\nG1 X2\nM3 S100\nM2\n");
  const CliRun r = interpret_cli_run("interpret " + program + " --count", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "2 moves, 1 events, program ends on line 5 (G-code (RS274/NGC))\n");
  const CliRun both = interpret_cli_run("interpret " + program + " --count --json");
  EXPECT_NE(both.exit_code, 0) << both.out;
}

// The options LinuxCNC's INI gives its interpreter: accepted by every command that reads a program, the
// subroutine path repeatable and colon-separated. (Whether a subroutine is found is the interpreter's test.)
TEST(InterpretCli, SubroutinePathAndParameterFileOptions) {
  const std::string program = interpret_cli_write_temp("plain.ngc", "G21 F100\nG1 X1\nM2\n");
  const CliRun r = interpret_cli_run(
      "interpret " + program + " --subroutine-path /tmp:/nonexistent/pkm" + " --subroutine-path /tmp --count",
      false);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  const CliRun orphan = interpret_cli_run("interpret " + program + " --write-parameter-file");
  EXPECT_NE(orphan.exit_code, 0) << orphan.out;
  for (const char* command : {"plan", "interpolate", "optimize", "stiffness", "modes-margin"}) {
    const CliRun help = interpret_cli_run(std::string(command) + " --help", false);
    EXPECT_NE(help.out.find("--subroutine-path"), std::string::npos) << command;
    EXPECT_NE(help.out.find("--parameter-file"), std::string::npos) << command;
  }
}

}  // namespace

namespace {

// A quarter arc entered tangentially, written as NX writes it (clockwise about the stated axis), in a file
// whose name says nothing: the reader goes by the content.
constexpr const char* kNxQuarter =
    "TOOL PATH/QUARTER,TOOL,MILL\nTLDATA/MILL,10.0000,0.0000,75.0000,0.0000,0.0000\n"
    "MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n"
    "FROM/10.0000,-5.0000,0.0000\nFEDRAT/MMPM,100.0000\nGOTO/"
    "10.0000,0.0000,0.0000,0.5000000,0.0000000,0.8660254\n"
    "CIRCLE/0.0000,0.0000,0.0000,0.0000000,0.0000000,-1.0000000,10.0000,0.0600,0.5000,10.0000,0.0000\n"
    "GOTO/0.0000,10.0000,0.0000\nEND-OF-PATH\n";

TEST(InterpretCliCl, TheDialectComesFromTheContentAndIsNamed) {
  const std::string program = interpret_cli_write_temp("quarter.nc", kNxQuarter);
  const CliRun r = interpret_cli_run("interpret " + program + " --count");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "2 moves, 4 events, program ends on line 9 (NX CLSF)\n");
  const CliRun json = interpret_cli_run("interpret " + program + " --json", false);
  ASSERT_EQ(json.exit_code, 0) << json.out;
  const auto document = nlohmann::json::parse(json.out);
  EXPECT_EQ(document["format"], "NX CLSF");
  const auto& arc = document["moves"][1];
  EXPECT_EQ(arc["kind"], "arc");
  EXPECT_NEAR(arc["normal"][2].get<double>(), 1.0, 1e-12);  // counter-clockwise in XY, as the path goes
  EXPECT_NEAR(arc["tool_axis"][0].get<double>(), 0.5, 1e-7);
}

TEST(InterpretCliCl, TheTableShowsTheToolAxis) {
  const std::string program = interpret_cli_write_temp("quarter_table.cls", kNxQuarter);
  const CliRun r = interpret_cli_run("interpret " + program, false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("tool i"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.5000    0.0000    0.8660"), std::string::npos) << r.out;
}

TEST(InterpretCliCl, AWrongFormatIsReportedAndAnUnknownOneRefused) {
  const std::string program = interpret_cli_write_temp("quarter_apt.cls", kNxQuarter);
  const CliRun apt = interpret_cli_run("interpret " + program + " --count --format apt");
  ASSERT_EQ(apt.exit_code, 0) << apt.out;
  EXPECT_NE(apt.out.find("1 arc(s) start against the direction of the move before them (lines 8)"),
            std::string::npos)
      << apt.out;
  const CliRun unknown = interpret_cli_run("interpret " + program + " --format mastercam");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(
      unknown.out.find("unknown format 'mastercam': one of auto, gcode, apt, nx, creo, catia, solidworks"),
      std::string::npos)
      << unknown.out;
}

TEST(InterpretCliCl, NoTransformKeepsTheClFrame) {
  std::string text = kNxQuarter;
  const std::string identity = "MSYS/0.0000,0.0000,0.0000,1.0000000";
  text.replace(text.find(identity), identity.size(), "MSYS/100.0000,0.0000,0.0000,1.0000000");
  const std::string program = interpret_cli_write_temp("quarter_frame.cls", text);
  const CliRun moved = interpret_cli_run("interpret " + program + " --json", false);
  const CliRun kept = interpret_cli_run("interpret " + program + " --json --no-transform", false);
  ASSERT_EQ(moved.exit_code, 0) << moved.out;
  ASSERT_EQ(kept.exit_code, 0) << kept.out;
  EXPECT_NEAR(nlohmann::json::parse(moved.out)["moves"][0]["end"][0].get<double>(), 110.0, 1e-9);
  EXPECT_NEAR(nlohmann::json::parse(kept.out)["moves"][0]["end"][0].get<double>(), 10.0, 1e-9);
}

}  // namespace
