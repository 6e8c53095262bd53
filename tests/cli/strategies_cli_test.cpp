// pkm strategies: the ranking as JSON, the files it writes, a given CL file ranked on its own (JSON and
// table), and the inputs it refuses without writing anything: an unknown surface kind, a non-positive
// semi-axis, a non-positive step-over, a cap as deep as the ellipsoid.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string strategies_cli_out(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_strategies_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

// A small cap and coarse passes at a low servo rate: the five runs take well under a second.
std::string strategies_cli_args(const std::string& out) {
  return "strategies --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
         " --load tangential=500,normal=150 --out " + out +
         " --surface ellipsoid:60,50,30 --depth-mm 2 --step-over-mm 8 --spacing-mm 4 --feed 2400 --rate 100";
}

TEST(StrategiesCli, RanksTheFiveStrategiesAndWritesTheirRuns) {
  const std::string out = strategies_cli_out("five");
  const auto run = test::run_pkm(strategies_cli_args(out) + " --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  const auto& rows = j["strategies"];
  ASSERT_EQ(rows.size(), 5u);
  std::set<std::string> names;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i]["rank"], static_cast<int>(i) + 1);
    names.insert(rows[i]["strategy"].get<std::string>());
    if (i > 0) {
      EXPECT_LE(rows[i - 1]["rms_normal_um"].get<double>(), rows[i]["rms_normal_um"].get<double>());
    }
    const std::string dir = out + "/" + rows[i]["strategy"].get<std::string>();
    for (const char* file : {"program.cl", "path.csv", "deflection.csv", "summary.json", "surface_error.csv"})
      EXPECT_TRUE(fs::exists(dir + "/" + file)) << dir << "/" << file;
  }
  EXPECT_EQ(names, (std::set<std::string>{"zigzag", "meridians", "parallels", "contour", "contour_loop"}));
  EXPECT_NE(j["criterion"].get<std::string>().find("rms"), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/strategies.csv"));
  EXPECT_TRUE(fs::exists(out + "/strategies.svg"));

  fs::remove_all(out);
}

TEST(StrategiesCli, RanksAGivenClFileAlone) {
  const std::string out = strategies_cli_out("given");
  const std::string args = "strategies --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                           " --load tangential=500 --rate 100 --out " + out + " --program " +
                           test::source_path("examples/programs/ball_end_5axis.cl");
  const auto run = test::run_pkm(args + " --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j["strategies"].size(), 1u);
  EXPECT_EQ(j["strategies"][0]["strategy"], "ball_end_5axis");
  EXPECT_GT(j["strategies"][0]["rms_normal_um"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(out + "/ball_end_5axis/deflection.csv"));
  EXPECT_FALSE(fs::exists(out + "/ball_end_5axis/program.cl"));  // planned where it is
  EXPECT_FALSE(fs::exists(out + "/zigzag"));
  // The table: the criterion and the one row.
  const auto table = test::run_pkm(args);
  ASSERT_EQ(table.exit_code, 0) << table.out;
  EXPECT_NE(table.out.find("ranked by the rms normal error"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("   1  ball_end_5axis"), std::string::npos) << table.out;
  fs::remove_all(out);
}

TEST(StrategiesCli, RefusesBadSurfacesAndStepOversWithoutWritingAnything) {
  const std::string out = strategies_cli_out("refused");
  const std::string machine = test::source_path("examples/machines/hexapod_ch5.yaml");
  const std::pair<std::string, std::string> cases[] = {
      {"--surface torus:60,50,30", "unknown surface kind 'torus'"},
      {"--surface ellipsoid:60,-5,30", "semi-axis b must be a positive length in mm, got -5"},
      {"--surface ellipsoid:60,0,30", "semi-axis b must be a positive length in mm, got 0"},
      {"--surface ellipsoid:60,50", "ellipsoid takes 3 semi-axes"},
      {"--step-over-mm 0", "--step-over-mm"},
      {"--step-over-mm -2", "--step-over-mm"},
      {"--surface ellipsoid:60,50,30 --depth-mm 30", "cap depth must be > 0 and < the semi-axis c"},
      {"--load tangential=abc", "--load"},
  };
  for (const auto& [args, words] : cases) {
    std::string line = "strategies --machine " + machine + " --out " + out + " " + args;
    if (args.find("--load") == std::string::npos) line += " --load tangential=500";
    const auto run = test::run_pkm(line);
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.out;
    EXPECT_NE(run.out.find(words), std::string::npos) << args << ": " << run.out;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace
}  // namespace pkm
