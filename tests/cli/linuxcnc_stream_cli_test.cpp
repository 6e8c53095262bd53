// pkm linuxcnc stream from the command line: the execution stream of a program (header, start, one record
// per period, end) equals the interpolation's steps.csv written beside it; its planned speeds stay within the
// execution headroom; a program the machine cannot follow exits 3 naming the line and leaves no `end`.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "interpolation/step_test_support.hpp"

namespace pkm {
namespace {

std::vector<std::vector<std::string>> records_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> records;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream text(line);
    for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
    records.push_back(fields);
  }
  return records;
}

TEST(LinuxcncStreamCli, TheStreamIsTheInterpolationsStepsWithinTheHeadroom) {
  const test::StepTempDir dir;
  const std::string stream = dir.file("line.stream");
  const auto run =
      test::run_pkm("linuxcnc stream --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                    " " + test::source_path("examples/programs/ch5_line.ngc") + " --to " + stream +
                    " --out " + dir.file("record"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto records = records_of(stream);
  const auto steps = test::read_csv_rows(dir.file("record/steps.csv"));
  ASSERT_EQ(records.size(), steps.rows.size() + 3);  // header, start, the periods, end
  EXPECT_EQ(records.front()[0].rfind("# pkm execution stream 1:", 0), 0u);
  EXPECT_EQ(records.back(), std::vector<std::string>{"end"});
  ASSERT_EQ(records[1][0], "start");
  double fastest_mm_s = 0.0;
  for (std::size_t k = 0; k < steps.rows.size(); ++k) {
    const auto& p = records[k + 2];
    const auto& row = steps.rows[k];
    ASSERT_EQ(p.size(), 14u);
    EXPECT_EQ(p[0], "p");
    EXPECT_EQ(p[1], row[2]);  // the program line
    for (int j = 0; j < 6; ++j) {
      EXPECT_EQ(p[8 + j], row[9 + j]) << "period " << k;                    // the whole steps, as steps.csv
      EXPECT_LE(std::abs(std::stod(p[2 + j]) - std::stod(p[8 + j])), 1.0);  // the ideal value within a step
      const auto& before = k == 0 ? records[1][1 + j] : records[k + 1][8 + j];
      fastest_mm_s =
          std::max(fastest_mm_s, std::abs(std::stod(p[8 + j]) - std::stod(before)) * 0.001 / 0.001);
    }
  }
  // Planned within 100 mm/s / 1.2 (one step of rounding at most).
  EXPECT_LE(fastest_mm_s, 100.0 / 1.2 + 1.0);
  EXPECT_GT(fastest_mm_s, 0.5 * 100.0 / 1.2);
}

TEST(LinuxcncStreamCli, AProgramOutOfReachExitsNamingTheLineAndTheStreamHasNoEnd) {
  const test::StepTempDir dir;
  const std::string stream = dir.file("out.stream");
  const std::string program = dir.file("far.ngc");
  std::ofstream(program) << "G21 G90\nG1 Z400 F600\nM2\n";
  const auto run =
      test::run_pkm("linuxcnc stream --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                    " " + program + " --to " + stream);
  EXPECT_EQ(run.exit_code, 3) << run.out;
  EXPECT_NE(run.out.find("far.ngc:2"), std::string::npos) << run.out;
  EXPECT_FALSE(std::filesystem::exists(stream));  // a file target appears only complete
}

TEST(LinuxcncStreamCli, AMachineWithoutDriveLimitsExitsTwoNamingTheKeys) {
  const test::StepTempDir dir;
  std::ifstream in(test::source_path("examples/machines/hexapod_ch5.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto at = yaml.find("  actuator_accel:");
  ASSERT_NE(at, std::string::npos);
  yaml.erase(at, yaml.find('\n', at) - at + 1);
  const std::string machine = dir.file("no_accel.yaml");
  std::ofstream(machine) << yaml;
  const auto run =
      test::run_pkm("linuxcnc stream --machine " + machine + " " +
                    test::source_path("examples/programs/ch5_line.ngc") + " --to " + dir.file("s"));
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("limits.actuator_accel"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace pkm
