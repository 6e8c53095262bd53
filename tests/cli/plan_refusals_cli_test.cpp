// pkm plan refuses what it cannot plan truthfully, with the program line: coordinates the machine does not
// control, plans whose actuators leave the path, programs out of reach (with the whole excursion and the
// translation that brings them inside), and work without bound; it warns of what the machine file leaves
// unchecked; and nothing is written by a refused run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string refusal_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_plan_refusal_" + name);
  fs::remove_all(dir);
  return dir.string();
}

test::CliRun plan(const std::string& program_text, const std::string& machine, const std::string& out,
                  const std::string& extra = "") {
  const std::string program =
      test::write_temp_file("refusal_" + fs::path(out).filename().string() + ".ngc", program_text);
  return test::run_pkm("plan " + program + " --machine " + test::source_path("examples/machines/" + machine) +
                       " --out " + out + " " + extra);
}

TEST(PlanRefusals, ATripodRefusesAnXyPocketNamingXAndItsLine) {
  const std::string out = refusal_dir("tripod");
  const auto run = plan("G21 G90\nG0 Z-5\nG1 X20 Y0 F600\nG1 Y20\nM2\n", "tripod.yaml", out);
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find(":3: X is not a controlled coordinate of example 3-RPS tripod"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("it follows from Z, A, B"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(PlanRefusals, ATriceptRefusesTurningA) {
  const std::string out = refusal_dir("tricept");
  const auto run = plan("G21 G90\nG1 X5 F600\nG1 A-360\nM2\n", "tricept.yaml", out);
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find(":3: A is not a controlled coordinate"), std::string::npos) << run.out;
}

// The ch3 hexapod's file gives neither limits nor a program origin: a square at program Z0 is at its base
// plane, where the forward kinematics of the planned actuators is another assembly mode, 400 mm away.
TEST(PlanRefusals, AMachineWithoutOriginOrLimitsWarnsAndRefusesThePlanOffThePath) {
  const std::string out = refusal_dir("ch3");
  const auto run =
      plan("G21 G90\nG0 X0 Y0 Z0\nG1 X20 F600\nG1 Y20\nG1 X0\nG1 Y0\nM2\n", "hexapod_ch3.yaml", out);
  EXPECT_EQ(run.exit_code, 3) << run.out;
  EXPECT_NE(run.out.find("warning: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("no motion.program_origin_mm"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("no limits.actuator_min/actuator_max"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("off the path"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(PlanRefusals, AProgramOutOfReachIsReportedWholeWithTheOffsetThatBringsItInside) {
  const std::string out = refusal_dir("excursion");
  // Inside, out along +Y to Y 600 and back: the excursion spans lines 4 to 6.
  const std::string text = "G21 G90\nG1 X0 Y0 Z0 F3000\nG1 Y60\nG1 Y600\nG1 X10\nG1 Y60\nG1 Y0\nM2\n";
  const auto run = plan(text, "hexapod_ch5.yaml", out, "--json");
  EXPECT_EQ(run.exit_code, 3) << run.out;
  EXPECT_NE(run.out.find("outside the workspace from line 4 to line 6"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("largest excess: actuator_"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
  const std::size_t json_start = run.out.find("{\n");
  ASSERT_NE(json_start, std::string::npos) << run.out;
  std::string json_text = run.out.substr(json_start);
  json_text = json_text.substr(0, json_text.find("\n}\n") + 2);
  const nlohmann::json error = nlohmann::json::parse(json_text)["error"];
  EXPECT_EQ(error["code"], "limit exceeded");
  EXPECT_EQ(error["line"], 4);
  const nlohmann::json& details = error["details"];
  ASSERT_EQ(details["excursions"].size(), 1u) << details.dump();
  EXPECT_EQ(details["excursions"][0]["first_line"], 4);
  EXPECT_EQ(details["excursions"][0]["last_line"], 6);
  ASSERT_FALSE(details["largest"].empty());
  EXPECT_GT(details["largest"][0]["excess"].get<double>(), 0.0);
  // The offset it offers, applied, plans.
  ASSERT_TRUE(details["offset_mm"].is_array()) << details.dump();
  const double dx = details["offset_mm"][0], dy = details["offset_mm"][1], dz = details["offset_mm"][2];
  // Added to the machine file's program origin, it plans.
  std::ifstream machine_in(test::source_path("examples/machines/hexapod_ch5.yaml"));
  std::stringstream machine_text;
  machine_text << machine_in.rdbuf();
  std::string yaml = machine_text.str();
  const std::string origin = "program_origin_mm: [0, 0, 700]";
  ASSERT_NE(yaml.find(origin), std::string::npos);
  std::ostringstream new_origin;
  new_origin << "program_origin_mm: [" << dx << ", " << dy << ", " << 700 + dz << "]";
  yaml.replace(yaml.find(origin), origin.size(), new_origin.str());
  const std::string machine = test::write_temp_file("refusal_offset_machine.yaml", yaml);
  const std::string program = test::write_temp_file("refusal_offset.ngc", text);
  const std::string out2 = refusal_dir("excursion_moved");
  const auto moved_run = test::run_pkm("plan " + program + " --machine " + machine + " --out " + out2);
  EXPECT_EQ(moved_run.exit_code, 0) << moved_run.out;
  fs::remove_all(out2);
}

TEST(PlanRefusals, WorkWithoutBoundIsRefusedUpFrontAtItsLine) {
  const std::string out = refusal_dir("bounds");
  const auto slow = plan("G21 G90\nG1 X1 F600\nG1 X10 F0.000001\nM2\n", "hexapod_ch5.yaml", out);
  EXPECT_EQ(slow.exit_code, 3) << slow.out;
  EXPECT_NE(slow.out.find("--max-ticks"), std::string::npos) << slow.out;
  EXPECT_NE(slow.out.find("slowest stretch is at line 3"), std::string::npos) << slow.out;
  const auto turns = plan("G21 G90\nG1 X10 F600\nG2 X10 Y0 I-10 J0 P1000000\nM2\n", "hexapod_ch5.yaml", out);
  EXPECT_EQ(turns.exit_code, 3) << turns.out;
  EXPECT_NE(turns.out.find(":3: the path needs"), std::string::npos) << turns.out;
  EXPECT_NE(turns.out.find("--max-samples"), std::string::npos) << turns.out;
  // The bound is the user's: a short program over a small one.
  const auto small = plan("G21 G90\nG1 X10 F600\nM2\n", "hexapod_ch5.yaml", out, "--max-ticks 100");
  EXPECT_EQ(small.exit_code, 3) << small.out;
  EXPECT_NE(small.out.find("bound of 100 ticks"), std::string::npos) << small.out;
  EXPECT_FALSE(fs::exists(out));
}

// The plan is made as the ticks stream, so a refusal can come after thousands of ticks were written: the
// folder then keeps the previous run's files, whole and unchanged, and nothing of the refused run.
TEST(PlanRefusals, ARefusalAfterTicksWereWrittenKeepsThePreviousRunWhole) {
  const std::string out = refusal_dir("late");
  const auto first = plan("G21 G90\nG1 X5 F600\nM2\n", "hexapod_ch5.yaml", out);
  ASSERT_EQ(first.exit_code, 0) << first.out;
  const auto listing = [&out] {
    std::map<std::string, std::uintmax_t> files;
    for (const auto& entry : fs::recursive_directory_iterator(out))
      files[entry.path().lexically_relative(out).string()] =
          entry.is_regular_file() ? entry.file_size() : std::uintmax_t{0};
    return files;
  };
  std::ifstream summary_in(fs::path(out) / "summary.json");
  const std::string summary_before((std::istreambuf_iterator<char>(summary_in)), {});
  const auto before = listing();
  // Forty seconds of motion inside, then a move out of reach; a window of a few moves, so that the ticks of
  // the first part are written before the planner meets the last move.
  std::string text = "G21 G90\nG1 X0 Y0 Z0 F600\n";
  for (int k = 0; k < 200; ++k) text += k % 2 == 0 ? "G1 X20\n" : "G1 X0\n";
  text += "G1 Y600\nM2\n";
  const auto refused = plan(text, "hexapod_ch5.yaml", out, "--lookahead-moves 4 --progress always");
  EXPECT_EQ(refused.exit_code, 3) << refused.out;
  EXPECT_NE(refused.out.find("outside the workspace from line 203"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("k ticks"), std::string::npos) << "ticks were written first: " << refused.out;
  EXPECT_EQ(listing(), before);
  std::ifstream summary_after_in(fs::path(out) / "summary.json");
  const std::string summary_after((std::istreambuf_iterator<char>(summary_after_in)), {});
  EXPECT_EQ(summary_after, summary_before);
  fs::remove_all(out);
}

TEST(PlanRefusals, APlanThatIsWrittenHoldsItsClaims) {
  const std::string out = refusal_dir("holds");
  const auto run =
      test::run_pkm("plan " + test::source_path("examples/programs/pocket.ngc") + " --machine " +
                        test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + out + " --json",
                    false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_LE(summary["max_feed_ratio"].get<double>(), 1.0);
  EXPECT_LE(summary["max_path_error_mm"].get<double>(), summary["path_error_bound_mm"].get<double>());
  EXPECT_TRUE(summary["warnings"].empty()) << summary["warnings"].dump();
  fs::remove_all(out);
}

// A program whose file name holds bytes that are not UTF-8 (a Latin-1 disk) plans: the summary names it with
// U+FFFD where such bytes were, rather than the run ending in an exception after all its work.
TEST(PlanRefusals, AProgramWhoseNameIsNotUtf8IsPlannedAndSummarised) {
  const fs::path dir = fs::temp_directory_path() / "pkm_plan_latin1";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path program = dir /
                           "pi\xe8"
                           "ce.ngc";
  std::ofstream(program) << "G21 G90\nG1 X5 F600\nM2\n";
  const auto run = test::run_pkm("plan '" + program.string() + "' --machine " +
                                     test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " +
                                     (dir / "out").string() + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  std::ifstream in(dir / "out" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_NE(summary["program"].get<std::string>().find("pi\xef\xbf\xbd"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pkm
