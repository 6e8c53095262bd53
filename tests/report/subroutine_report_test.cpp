// A planned program that calls subroutines, one in a file of its own on the subroutine path and one defined
// in the program: summary.json names, per calling line, where the moves it executes were written, and the
// report's program carries the same for the lines it shows; a program without calls has no such key.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pipeline/plan_program.hpp"
#include "report/report_data.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

fs::path subroutine_report_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("pkm_subroutine_report_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir / "subs");
  return dir;
}

nlohmann::json subroutine_report_summary(const fs::path& dir) {
  std::ifstream in(dir / "plan" / "summary.json");
  return nlohmann::json::parse(in);
}

// Line 7 calls drill_hole.ngc (its moves on that file's lines 2–4), line 8 calls bolt, defined on lines 2–5.
constexpr const char* kSubroutineReportMain =
    "G21 G90 G17 G94\n"
    "o<bolt> sub\n"
    "G1 X#1 Y0 Z2 F600\n"
    "G1 Z0\n"
    "o<bolt> endsub\n"
    "G0 X0 Y0 Z5\n"
    "o<drill_hole> call [5] [5]\n"
    "o<bolt> call [-5]\n"
    "G1 X0 Y0 Z5 F600\n"
    "M2\n";
constexpr const char* kSubroutineReportDrill =
    "o<drill_hole> sub\n"
    "G0 X#1 Y#2 Z5\n"
    "G1 Z0 F300\n"
    "G0 Z5\n"
    "o<drill_hole> endsub\n"
    "M2\n";

TEST(SubroutineReport, SummaryAndReportNameWhereCalledMovesWereWritten) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const fs::path dir = subroutine_report_dir("calls");
  std::ofstream(dir / "bolt.ngc") << kSubroutineReportMain;
  std::ofstream(dir / "subs" / "drill_hole.ngc") << kSubroutineReportDrill;

  pipeline::PlanJob job;
  job.program_path = (dir / "bolt.ngc").string();
  job.program_options.subroutine_path = {(dir / "subs").string()};
  job.out_directory = (dir / "plan").string();
  auto planned = pipeline::plan_program(machine, job);
  ASSERT_TRUE(planned) << planned.error().message;

  const nlohmann::json expected = {{"7", {"drill_hole.ngc:2", "drill_hole.ngc:3", "drill_hole.ngc:4"}},
                                   {"8", {"bolt.ngc:3", "bolt.ngc:4"}}};
  const nlohmann::json summary = subroutine_report_summary(dir);
  ASSERT_TRUE(summary.contains("subroutine_lines")) << summary.dump(2);
  EXPECT_EQ(summary["subroutine_lines"], expected);
  EXPECT_EQ(planned->summary["subroutine_lines"], expected);

  auto report = report::report_from_directory((dir / "plan").string());
  ASSERT_TRUE(report) << report.error().message;
  const nlohmann::json& program = (*report)["program"];
  ASSERT_TRUE(program.contains("subroutine_lines")) << program.dump(2);
  EXPECT_EQ(program["subroutine_lines"], expected);
  EXPECT_EQ(program["lines"].value("7", ""), "o<drill_hole> call [5] [5]");
  fs::remove_all(dir);
}

TEST(SubroutineReport, ProgramWithoutCallsHasNoSubroutineLines) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const fs::path dir = subroutine_report_dir("plain");
  std::ofstream(dir / "plain.ngc") << "G21 G90\nG0 X0 Y0 Z5\nG1 X10 Y5 Z0 F600\nM2\n";
  pipeline::PlanJob job;
  job.program_path = (dir / "plain.ngc").string();
  job.out_directory = (dir / "plan").string();
  auto planned = pipeline::plan_program(machine, job);
  ASSERT_TRUE(planned) << planned.error().message;
  EXPECT_FALSE(subroutine_report_summary(dir).contains("subroutine_lines"));
  EXPECT_FALSE(planned->summary.contains("subroutine_lines"));
  auto report = report::report_from_directory((dir / "plan").string());
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_FALSE((*report)["program"].contains("subroutine_lines"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pkm
