// pkm optimize and pkm plan --law from the command line: the summary, the written program, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string fresh_path(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("pkm_optimize_cli_" + name);
  fs::remove_all(path);
  return path.string();
}

std::string planar_args() {
  return test::source_path("examples/programs/planar_circle.ngc") + " --machine " +
         test::source_path("examples/machines/planar3.yaml") + " --step-mm 0.6981317";
}

TEST(OptimizeCli, PlanarCircleSummaryAndProgram) {
  const std::string out = fresh_path("planar.ngc");
  const auto run =
      test::run_pkm("optimize " + planar_args() + " --law increment --out " + out + " --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  for (const char* key : {"const_sum_mm", "opt_sum_mm", "peak_force_const_N", "peak_force_opt_N",
                          "energy_const_J", "energy_opt_J", "free_range_deg"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_NEAR(summary["const_sum_mm"].get<double>(), 227.89, 1.0);
  EXPECT_NEAR(summary["opt_sum_mm"].get<double>(), 207.84, 1.0);
  EXPECT_EQ(summary["free_coordinates"][0], "phi");
  // The program: every feed line carries the chosen phi as C, and it runs through pkm interpret.
  std::ifstream in(out);
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("G3"), std::string::npos);
  EXPECT_NE(text.str().find(" C1"), std::string::npos);
  const auto interpreted = test::run_pkm("interpret " + out + " --json", false);
  ASSERT_EQ(interpreted.exit_code, 0) << interpreted.out;
  const auto moves = nlohmann::json::parse(interpreted.out)["moves"];
  EXPECT_GE(moves.size(), 361u);
}

TEST(OptimizeCli, BadArgumentsFailWithoutOutput) {
  const std::string out = fresh_path("bad.ngc");
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {" --law fastest", "--law fastest"},
      {" --law increment --free some", "--free some"},
      {" --law increment --bounds 30", "--bounds 30"},
      {" --law increment --bounds 20,30", "outside the bounds 20,30"},
      {" --law force --load tangential=abc", "tangential"},
      {" --law increment --solver quantum", "--solver quantum"},
      {" --law energy --force-model newton", "--force-model newton"},
      {" --law energy --force-model dynamics", "dynamics: section"},  // planar3.yaml has none
      {" --law increment --parts some", "--parts some"},
      {" --law increment --bounds 5,30,5", "--bounds 5,30,5"},
      {" --law increment --bounds 5,30,5,30,5,30", "3 ranges"},
      {" --law increment --parts adaptive --solver global", "--parts fixed"},
      {" --law increment --parts adaptive --improvement 1.5", "--improvement"},
      {" --law increment --parts adaptive --min-part-mm 0", "--min-part-mm"},
      {" --law increment --parts adaptive --patience 0", "--patience"},
  };
  for (const Case& c : cases) {
    const auto run = test::run_pkm("optimize " + planar_args() + c.args + " --out " + out);
    EXPECT_EQ(run.exit_code, 2) << c.args << ": " << run.out;
    EXPECT_NE(run.out.find(c.message), std::string::npos) << c.args << ": " << run.out;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

// Adaptive parts on a five-axis CAM program (CL data) on the hexaglide: the same criterion measured along
// the motion at the same step, written in fewer than half the blocks of the fixed step.
TEST(OptimizeCli, AdaptivePartsWriteFewerBlocksForTheSameCriterion) {
  const std::string args = test::source_path("examples/programs/ball_end_5axis.cl") + " --machine " +
                           test::source_path("examples/machines/hexaglide.yaml") +
                           " --law increment --step-mm 0.5 --json --out ";
  const std::string fixed_out = fresh_path("fixed.ngc");
  const std::string adaptive_out = fresh_path("adaptive.ngc");
  const auto fixed = test::run_pkm("optimize " + args + fixed_out, false);
  const auto adaptive = test::run_pkm("optimize " + args + adaptive_out + " --parts adaptive", false);
  ASSERT_EQ(fixed.exit_code, 0) << fixed.out;
  ASSERT_EQ(adaptive.exit_code, 0) << adaptive.out;
  const auto f = nlohmann::json::parse(fixed.out);
  const auto a = nlohmann::json::parse(adaptive.out);
  EXPECT_EQ(f["parts"], "fixed");
  EXPECT_EQ(a["parts"], "adaptive");
  EXPECT_EQ(a["improvement"].get<double>(), 0.01);
  EXPECT_EQ(a["min_part_mm"].get<double>(), 1.0);
  EXPECT_EQ(a["patience"].get<int>(), 3);
  EXPECT_LT(2 * a["parts_written"].get<int>(), f["parts_written"].get<int>());
  EXPECT_LT(a["opt_sum_mm"].get<double>(), 1.005 * f["opt_sum_mm"].get<double>());
  EXPECT_LT(a["opt_sum_mm"].get<double>(), 0.8 * a["const_sum_mm"].get<double>());
  EXPECT_NEAR(a["const_sum_mm"].get<double>(), f["const_sum_mm"].get<double>(),
              1e-3 * f["const_sum_mm"].get<double>());
  // The written program has one block per part after the approach, and LinuxCNC's dialect reads it back.
  const auto interpreted = test::run_pkm("interpret " + adaptive_out + " --json", false);
  ASSERT_EQ(interpreted.exit_code, 0) << interpreted.out;
  const auto moves = nlohmann::json::parse(interpreted.out)["moves"];
  EXPECT_GE(moves.size(), a["parts_written"].get<std::size_t>());
  EXPECT_LT(moves.size(), a["parts_written"].get<std::size_t>() + 20);
}

TEST(OptimizeCli, MachinesWithoutFreeCoordinatesAreRefused) {
  const std::string out = fresh_path("tripod.ngc");
  const auto run =
      test::run_pkm("optimize " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                    test::source_path("examples/machines/tripod.yaml") + " --law increment --out " + out);
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("controls no orientation"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(OptimizeCli, PlanWithLawReportsTheLaw) {
  const std::string dir = fresh_path("plan_law");
  const auto run = test::run_pkm(
      "plan " + planar_args() + " --law increment --bounds 5,30 --tables csv --out " + dir + " --json",
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  ASSERT_TRUE(summary.contains("redundancy"));
  EXPECT_LT(summary["redundancy"]["opt_sum_mm"].get<double>(),
            summary["redundancy"]["const_sum_mm"].get<double>());
  EXPECT_TRUE(fs::exists(fs::path(dir) / "actuators.csv"));
}

TEST(OptimizeCli, TheDynamicForceModelIsReportedAndChangesTheLaw) {
  const std::string program =
      test::write_temp_file("optimize_e1.ngc", "G21 G90 G17 G94\nG0 X-50 Y0 Z700\nG1 X50 Y0 F3000\nM2\n");
  const std::string args = "optimize " + program + " --machine " +
                           test::source_path("examples/machines/hexapod_ch3.yaml") +
                           " --law energy --free all --load tangential=707.1,normal=707.1 --json --out ";
  const auto statics = test::run_pkm(args + fresh_path("e1_statics.ngc"), false);
  const auto dynamics =
      test::run_pkm(args + fresh_path("e1_dynamics.ngc") + " --force-model dynamics", false);
  ASSERT_EQ(statics.exit_code, 0) << statics.out;
  ASSERT_EQ(dynamics.exit_code, 0) << dynamics.out;
  const auto s = nlohmann::json::parse(statics.out), d = nlohmann::json::parse(dynamics.out);
  EXPECT_EQ(s["force_model"], "statics");
  EXPECT_EQ(d["force_model"], "dynamics");
  // The dynamic model adds the struts' and platform's weights and inertia: other forces, other energies.
  EXPECT_GT(std::abs(d["energy_const_J"].get<double>() - s["energy_const_J"].get<double>()), 0.1);
  EXPECT_LT(d["energy_opt_J"].get<double>(), d["energy_const_J"].get<double>());
}

}  // namespace
}  // namespace pkm
