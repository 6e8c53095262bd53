// pkm modes-margin: the assembly-mode margin along a program on the shipped machines. The printed summary
// names the program line of the smallest margin, which is the smallest of the CSV's rows; --json gives the
// same numbers; bad input exits non-zero with a message naming the file, line or option and leaves a previous
// CSV as it was.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string mmc_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

std::string mmc_program(const std::string& file) {
  return test::source_path("examples/programs/" + file);
}

// A CSV path in the temporary directory with nothing there yet.
std::string mmc_out(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("pkm_modes_margin_cli_" + name + ".csv");
  fs::remove_all(path);
  return path.string();
}

std::string mmc_read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t mmc_column(const std::string& header, const std::string& name) {
  std::stringstream text(header);
  std::size_t index = 0;
  for (std::string field; std::getline(text, field, ','); ++index) {
    if (field == name) return index;
  }
  ADD_FAILURE() << name << " not in " << header;
  return 0;
}

TEST(ModesMarginCli, PrintsTheSmallestMarginWithItsLineAndWritesTheCsv) {
  const std::string out = mmc_out("ch5");
  const auto run = test::run_pkm("modes-margin " + mmc_program("ch5_line.ngc") + " --machine " +
                                 mmc_machine("hexapod_ch5.yaml") + " --samples 20 --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const test::CsvRows csv = test::read_csv_rows(out);
  EXPECT_EQ(csv.header.rfind("time_s,line,x_mm,y_mm,z_mm,", 0), 0u) << csv.header;
  ASSERT_EQ(csv.rows.size(), 22u);  // the start, 20 between, the end
  const std::size_t line_column = mmc_column(csv.header, "line");
  const std::size_t margin_column = mmc_column(csv.header, "margin_mm");
  const std::size_t status_column = mmc_column(csv.header, "margin_status");
  const std::size_t modes_column = mmc_column(csv.header, "real_modes");
  double smallest = INFINITY;
  std::string smallest_line;
  for (const auto& row : csv.rows) {
    ASSERT_GT(row.size(), margin_column);
    EXPECT_EQ(row[status_column], "found");
    EXPECT_GE(std::stoi(row[modes_column]), 2);  // the 6-3 hexapod enumerates its modes
    const double margin = std::stod(row[margin_column]);
    EXPECT_GT(margin, 0.0);
    if (margin < smallest) {
      smallest = margin;
      smallest_line = row[line_column];
    }
  }
  // The summary names the smallest row's margin and its program line.
  const std::string printed = fmt::format("min {:.3f} mm at line {},", smallest, smallest_line);
  EXPECT_NE(run.out.find(printed), std::string::npos) << printed << "\n" << run.out;
  EXPECT_NE(run.out.find("real assembly modes"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("written " + out), std::string::npos) << run.out;
}

TEST(ModesMarginCli, JsonSummaryMatchesTheCsv) {
  const std::string out = mmc_out("planar");
  const auto run = test::run_pkm("modes-margin " + mmc_program("planar_circle.ngc") + " --machine " +
                                     mmc_machine("planar3.yaml") + " --samples 8 --out " + out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["kind"], "modes_margin");
  EXPECT_EQ(j["samples"], 10);
  EXPECT_EQ(j["out"], out);
  ASSERT_TRUE(j["min_margin"].is_object()) << run.out;
  const test::CsvRows csv = test::read_csv_rows(out);
  ASSERT_EQ(csv.rows.size(), 10u);
  const std::size_t margin_column = mmc_column(csv.header, "margin_mm");
  double smallest = INFINITY;
  for (const auto& row : csv.rows) smallest = std::min(smallest, std::stod(row[margin_column]));
  EXPECT_NEAR(j["min_margin"]["margin_mm"].get<double>(), smallest, 1e-8 * smallest);
  EXPECT_GE(j["min_real_modes"].get<int>(), 2);
  EXPECT_LE(j["min_real_modes"].get<int>(), j["max_real_modes"].get<int>());
  const int line = j["min_margin"]["line"].get<int>();
  EXPECT_TRUE(line == 5 || line == 6) << line;  // the G0 and the G3 of planar_circle.ngc
}

TEST(ModesMarginCli, AGlideMachinesModesAreItsCarriagesGoughStewartPlatforms) {
  // A glide enumerates its modes as the Gough–Stewart platform its carriage joints make: every sample has
  // at least its own mode, and the margin is given.
  const std::string program = test::write_temp_file("modes_margin_glide.ngc", "G21 G90\nG1 X10 F600\nM2\n");
  const auto run = test::run_pkm(
      "modes-margin " + program + " --machine " + mmc_machine("hexaglide.yaml") + " --samples 3 --json",
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_GT(j["modes_enumerated"].get<int>(), 0);
  EXPECT_GE(j["min_real_modes"].get<int>(), 1);
  EXPECT_TRUE(j["min_margin"].is_object());
}

TEST(ModesMarginCli, BadInputExitsNonZeroNamingThePlaceAndKeepsAPreviousCsv) {
  const std::string out = mmc_out("kept");
  std::ofstream(out) << "previous\n";
  const std::string ch5 = mmc_machine("hexapod_ch5.yaml");
  const std::string line = mmc_program("ch5_line.ngc");
  const std::string climb =
      test::write_temp_file("modes_margin_climb.ngc", "G21 G90\nG0 X0 Y0 Z0\nG1 Z500 F600\nM2\n");
  const std::string broken_machine =
      test::write_temp_file("modes_margin_broken.yaml", "type: hexapod\nangles: krylov\nbase_joints: 7\n");
  struct Case {
    std::string arguments;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"/nonexistent/p.ngc --machine " + ch5, 2, "/nonexistent/p.ngc"},
      {line + " --machine /nonexistent/m.yaml", 2, "/nonexistent/m.yaml"},
      {line + " --machine " + broken_machine, 2, "modes_margin_broken.yaml:3:"},
      {line + " --machine " + ch5 + " --samples 0", 2, "--samples"},
      {line + " --machine " + ch5 + " --samples -4", 2, "--samples"},
      {line + " --machine " + ch5 + " --samples 2.5", 2, "--samples"},
      {climb + " --machine " + ch5, 3, "modes_margin_climb.ngc:3:"},
  };
  for (const Case& c : cases) {
    const auto run = test::run_pkm("modes-margin " + c.arguments + " --out " + out);
    EXPECT_EQ(run.exit_code, c.exit_code) << c.arguments << "\n" << run.out;
    EXPECT_NE(run.out.find("pkm modes-margin: error: "), std::string::npos) << c.arguments << "\n" << run.out;
    EXPECT_NE(run.out.find(c.message), std::string::npos) << c.arguments << "\n" << run.out;
    EXPECT_EQ(mmc_read(out), "previous\n") << c.arguments;
  }
}

}  // namespace
}  // namespace pkm
