// pkm spif from the command line: the forming program, the placement study's set of files, and bad input
// refused without output.
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
  const fs::path path = fs::temp_directory_path() / ("pkm_spif_cli_" + name);
  fs::remove_all(path);
  return path.string();
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SpifCli, TheSeedsStudyFromTheCommandLine) {
  const std::string program = fresh_path("cone.ngc");
  const auto written = test::run_pkm("spif program --out " + program, false);
  ASSERT_EQ(written.exit_code, 0) << written.out;
  EXPECT_NE(read(program).find("G3 X65.0000 Y0.0000 I-65.0000 J0"), std::string::npos);  // the 21st circle
  const std::string dir = fresh_path("placement");
  const auto run = test::run_pkm("spif placement " + program + " --machine " +
                                     test::source_path("examples/machines/hexapod_ch3.yaml") +
                                     " --z1 300:700:200 --load axial=2500,tangential=1400,normal=350,"
                                     "cutter_radius=12.5 --out " +
                                     dir + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  ASSERT_EQ(summary["placements"].size(), 3u);
  EXPECT_EQ(summary["lowest_energy"]["z1_mm"].get<double>(), 700.0);
  EXPECT_EQ(summary["highest_energy"]["z1_mm"].get<double>(), 300.0);
  EXPECT_GT(summary["energy_ratio"].get<double>(), 2.0);
  EXPECT_EQ(nlohmann::json::parse(read(dir + "/summary.json"))["energy_ratio"], summary["energy_ratio"]);
  // placement.csv: 21 planes at each height, adding up to the feed moves' share of each total.
  std::istringstream csv(read(dir + "/placement.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "z1_mm,plane,plane_z_mm,first_line,energy_J,law_energy_J");
  std::map<double, double> sums;
  int rows = 0;
  while (std::getline(csv, line)) {
    double z1 = 0.0, energy = 0.0;
    int plane = 0, first = 0;
    double plane_z = 0.0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%d,%lf,%d,%lf", &z1, &plane, &plane_z, &first, &energy), 5)
        << line;
    sums[z1] += energy;
    ++rows;
  }
  EXPECT_EQ(rows, 63);
  for (const auto& row : summary["placements"]) {
    const double total = row["energy_J"].get<double>();
    EXPECT_NEAR(sums[row["z1_mm"].get<double>()], total, 0.01 * total);
  }
  EXPECT_NE(read(dir + "/placement.svg").find("<svg"), std::string::npos);
  // A range of fractional steps ends on its last height exactly.
  const auto fine = test::run_pkm("spif placement " + program + " --machine " +
                                      test::source_path("examples/machines/hexapod_ch3.yaml") +
                                      " --z1 700.1:700.3:0.1 --out " + fresh_path("fine") + " --json",
                                  false);
  ASSERT_EQ(fine.exit_code, 0) << fine.out;
  const auto heights = nlohmann::json::parse(fine.out)["placements"];
  ASSERT_EQ(heights.size(), 3u);
  EXPECT_NEAR(heights[2]["z1_mm"].get<double>(), 700.3, 1e-9);
}

TEST(SpifCli, BadInputIsNamedAndWritesNothing) {
  const std::string program = fresh_path("bad.ngc");
  const auto bad_program = test::run_pkm("spif program --radius-step-mm 10 --out " + program);
  EXPECT_EQ(bad_program.exit_code, 2) << bad_program.out;
  EXPECT_NE(bad_program.out.find("radius step"), std::string::npos) << bad_program.out;
  EXPECT_FALSE(fs::exists(program));
  const std::string cone = fresh_path("ok.ngc");
  ASSERT_EQ(test::run_pkm("spif program --out " + cone).exit_code, 0);
  const std::string dir = fresh_path("bad_placement");
  const std::string machine = " --machine " + test::source_path("examples/machines/hexapod_ch5.yaml");
  struct Case {
    std::string args;
    std::string message;
    int exit_code;
  };
  for (const Case& c : {Case{" --z1 300:700", "--z1 300:700", 2}, Case{" --z1 700:300:50", "--z1", 2},
                        Case{" --z1 a,b", "--z1 a,b", 2}, Case{" --z1 0 --load axial=x", "axial", 2},
                        Case{" --z1 0 --law fastest", "--law fastest", 2},
                        Case{" --z1 0 --bounds -5,5", "--bounds needs --law", 2},
                        Case{" --z1 1000,2000", "at no height", 3}}) {
    const auto run = test::run_pkm("spif placement " + cone + machine + c.args + " --out " + dir);
    EXPECT_EQ(run.exit_code, c.exit_code) << c.args << ": " << run.out;
    EXPECT_NE(run.out.find(c.message), std::string::npos) << c.args << ": " << run.out;
    EXPECT_FALSE(fs::exists(dir)) << c.args;
  }
}

}  // namespace
}  // namespace pkm
