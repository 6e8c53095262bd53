// pkm calibrate plan | simulate | identify (docs/calibration.md) on the ch5 hexapod:
//  - plan: the poses of plan.csv are within the machine's actuator travel, their readings are the IK of their
//    poses, and the summary states rank and predicted accuracy; a plan that cannot identify every parameter
//    is reported as such, and with --strict refused without output;
//  - simulate → identify: a noise-free simulated measurement file is identified back to its true parameters
//    (1e-6 mm), the calibrated machine file loads and `pkm ik` and `pkm plan` accept it, and its report is a
//    calibration report;
//  - bad measurement files (too few poses, NaN, other units, a reading beyond the travel) exit 2 naming
//    file:line:column and leave no output.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

const std::string kCalcliMachine = test::source_path("examples/machines/hexapod_ch5.yaml");

fs::path calcli_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_calibrate_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A CSV file as rows of text fields, by column name.
struct CalcliTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

CalcliTable calcli_read(const fs::path& path) {
  CalcliTable table;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    if (table.columns.empty())
      table.columns = fields;
    else
      table.rows.push_back(fields);
  }
  return table;
}

nlohmann::json calcli_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(CalibrateCli, PlanWritesPosesWithinTheLimitsAndItsPrediction) {
  const fs::path dir = calcli_dir("plan");
  const auto run = test::run_pkm(fmt::format(
      "calibrate plan --machine {} --method d-optimal --poses 10 --candidates 60 --held-out 10 --out {}",
      kCalcliMachine, (dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const CalcliTable plan = calcli_read(dir / "out" / "plan.csv");
  ASSERT_EQ(plan.rows.size(), 10u);
  for (const auto& row : plan.rows) {
    for (int j = 1; j <= 6; ++j) {
      const double length = std::stod(row[plan.column(fmt::format("L{}", j))]);
      EXPECT_GE(length, 350.0);
      EXPECT_LE(length, 900.0);
    }
  }
  // The readings are the inverse kinematics of the pose on the same row.
  const auto& first = plan.rows.front();
  const std::string pose =
      fmt::format("{},{},{},{},{},{}", first[1], first[2], first[3], first[4], first[5], first[6]);
  const auto ik = test::run_pkm(fmt::format("ik --machine {} --pose={} --json", kCalcliMachine, pose));
  ASSERT_EQ(ik.exit_code, 0) << ik.out;
  const nlohmann::json lengths = nlohmann::json::parse(ik.out);
  ASSERT_TRUE(lengths.contains("actuators")) << ik.out;
  EXPECT_NEAR(lengths["actuators"][2].get<double>(), std::stod(first[plan.column("L3")]), 1e-6);
  const nlohmann::json summary = calcli_json(dir / "out" / "summary.json");
  EXPECT_EQ(summary["poses"], 10);
  EXPECT_EQ(summary["identifiability"]["parameters"], 42);  // 36 joint coordinates and 6 drive offsets
  EXPECT_EQ(summary["identifiability"]["rank"], 42);
  EXPECT_GT(summary["predicted_tool_error_mm"]["rms"].get<double>(), 0.0);

  // The dissertation's seven poses: n + 1 of them.
  const auto seven =
      test::run_pkm(fmt::format("calibrate plan --machine {} --method seven-pose --held-out 5 --out {}",
                                kCalcliMachine, (dir / "seven").string()));
  ASSERT_EQ(seven.exit_code, 0) << seven.out;
  EXPECT_EQ(calcli_read(dir / "seven" / "plan.csv").rows.size(), 7u);
}

TEST(CalibrateCli, AnUnidentifiablePlanIsReportedAndRefusedWhenStrict) {
  const fs::path dir = calcli_dir("unidentifiable");
  // Ten ballbar lengths cannot determine 42 parameters.
  const std::string args = fmt::format(
      "calibrate plan --machine {} --method random --poses 10 --held-out 5 --ballbar-centre 0,0,500 --out {}",
      kCalcliMachine, (dir / "out").string());
  const auto run = test::run_pkm(args);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("not identifiable"), std::string::npos) << run.out;
  const nlohmann::json summary = calcli_json(dir / "out" / "summary.json");
  EXPECT_FALSE(summary["identifiability"]["identifiable"].get<bool>());
  EXPECT_LE(summary["identifiability"]["rank"].get<int>(), 10);
  EXPECT_FALSE(summary["identifiability"]["unidentifiable_combinations"].empty());

  const fs::path strict_dir = dir / "strict";
  const auto strict =
      test::run_pkm(fmt::format("calibrate plan --machine {} --method random --poses 10 --held-out 5 "
                                "--ballbar-centre 0,0,500 --strict --out {}",
                                kCalcliMachine, strict_dir.string()));
  EXPECT_EQ(strict.exit_code, 4) << strict.out;
  EXPECT_FALSE(fs::exists(strict_dir)) << strict.out;
}

TEST(CalibrateCli, SimulatedMeasurementsAreIdentifiedBackAndTheCalibratedFileIsUsable) {
  const fs::path dir = calcli_dir("round_trip");
  const fs::path measurements = dir / "measured.csv";
  const auto simulated = test::run_pkm(
      fmt::format("calibrate simulate --machine {} --method random --poses 14 --held-out 5 --trials 2 "
                  "--joint-error-mm 0.2 "
                  "--offset-error-mm 0.3 --seed 7 --write-measurements {} --noise-free --out {}",
                  kCalcliMachine, measurements.string(), (dir / "sim").string()));
  ASSERT_EQ(simulated.exit_code, 0) << simulated.out;
  ASSERT_TRUE(fs::exists(measurements));
  ASSERT_TRUE(fs::exists(dir / "measured_fixture.csv"));
  const CalcliTable trials = calcli_read(dir / "sim" / "trials.csv");
  EXPECT_EQ(trials.rows.size(), 2u);

  const fs::path calibrated = dir / "calibrated.yaml";
  // The report is asked for only where the page is built (a build without Node.js refuses every report).
  const std::string report_flag =
      PKM_REPORT_PAGE ? fmt::format(" --report {}", (dir / "report.html").string()) : std::string();
  const auto identified = test::run_pkm(fmt::format(
      "calibrate identify --machine {} --measurements {} --out {} --dir {} --holdout 2{}", kCalcliMachine,
      measurements.string(), calibrated.string(), (dir / "id").string(), report_flag));
  ASSERT_EQ(identified.exit_code, 0) << identified.out;
  const CalcliTable truth = calcli_read(dir / "sim" / "true_parameters.csv");
  const CalcliTable found = calcli_read(dir / "id" / "parameters.csv");
  ASSERT_EQ(truth.rows.size(), 42u);
  ASSERT_EQ(found.rows.size(), truth.rows.size());
  double largest_change = 0.0;
  for (std::size_t i = 0; i < truth.rows.size(); ++i) {
    EXPECT_EQ(found.rows[i][found.column("name")], truth.rows[i][truth.column("name")]);
    const double true_value = std::stod(truth.rows[i][truth.column("true")]);
    EXPECT_NEAR(std::stod(found.rows[i][found.column("identified")]), true_value, 1e-6)
        << truth.rows[i][truth.column("name")];
    EXPECT_EQ(found.rows[i][found.column("identifiable")], "yes");
    largest_change = std::max(largest_change, std::abs(std::stod(truth.rows[i][truth.column("change")])));
  }
  EXPECT_GT(largest_change, 0.1);  // there was something to find
  const nlohmann::json summary = calcli_json(dir / "id" / "summary.json");
  EXPECT_EQ(summary["status"], "identified");
  EXPECT_EQ(summary["held_out"]["poses"], 2);
  EXPECT_LT(summary["held_out"]["max_after_mm"].get<double>(), 1e-6);
  EXPECT_GT(summary["held_out"]["max_before_mm"].get<double>(), 0.05);
  EXPECT_TRUE(fs::exists(dir / "id" / "residuals.csv"));

  // Every other command reads the calibrated file.
  const auto ik = test::run_pkm(fmt::format("ik --machine {} --pose=0,0,700,0,0,0", calibrated.string()));
  EXPECT_EQ(ik.exit_code, 0) << ik.out;
  const auto planned = test::run_pkm(fmt::format("plan {} --machine {} --out {}",
                                                 test::source_path("examples/programs/ch5_line.ngc"),
                                                 calibrated.string(), (dir / "plan").string()));
  EXPECT_EQ(planned.exit_code, 0) << planned.out;
#if PKM_REPORT_PAGE
  std::ifstream page(dir / "report.html");
  std::stringstream html;
  html << page.rdbuf();
  EXPECT_NE(html.str().find("\"kind\":\"calibration\""), std::string::npos);
#endif
}

// A measurement file built from the example's first rows with one change, and the identify command on it.
struct CalcliBadRun {
  test::CliRun run;
  fs::path calibrated, out;
};

CalcliBadRun calcli_identify_bad(const std::string& name, const std::string& text) {
  const fs::path dir = calcli_dir("bad_" + name);
  fs::copy_file(test::source_path("examples/calibration/plate_fixture.csv"), dir / "plate_fixture.csv");
  std::ofstream(dir / "m.csv") << text;
  CalcliBadRun bad{{}, dir / "calibrated.yaml", dir / "id"};
  bad.run = test::run_pkm(fmt::format("calibrate identify --machine {} --measurements {} --out {} --dir {}",
                                      kCalcliMachine, (dir / "m.csv").string(), bad.calibrated.string(),
                                      bad.out.string()));
  return bad;
}

std::string calcli_example() {
  std::ifstream in(test::source_path("examples/calibration/hexapod_ch5_tracker.csv"));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The example with the first occurrence of `from` after the column row replaced by `to`.
std::string calcli_edit(const std::string& from, const std::string& to) {
  std::string text = calcli_example();
  const std::size_t at = text.find(from, text.find("pose_id"));
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(CalibrateCli, BadMeasurementFilesExitNamingTheirPlaceAndWriteNothing) {
  const std::string example = calcli_example();
  ASSERT_NE(example.find("pose_id"), std::string::npos);
  // The line of the first data row, and its third field's column.
  int header_line = 1;
  for (std::size_t i = 0; i < example.find("pose_id"); ++i) header_line += example[i] == '\n' ? 1 : 0;
  const std::size_t row_start = example.find('\n', example.find("pose_id")) + 1;
  const std::string first_row = example.substr(row_start, example.find('\n', row_start) - row_start);
  const std::size_t l2 = first_row.find(',', first_row.find(',') + 1) + 1;
  const std::string l2_text = first_row.substr(l2, first_row.find(',', l2) - l2);

  struct Case {
    std::string name, text, place;
  };
  const std::vector<Case> cases = {
      {"nan", calcli_edit("," + l2_text + ",", ",nan,"),
       fmt::format("m.csv:{}:{}: L2:", header_line + 1, l2 + 1)},
      {"beyond", calcli_edit("," + l2_text + ",", ",950,"),
       fmt::format("m.csv:{}:{}: L2:", header_line + 1, l2 + 1)},
      {"few", example.substr(0, example.find('\n', row_start) + 1),
       fmt::format("m.csv:{}:1: pose_id:", header_line + 1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const CalcliBadRun bad = calcli_identify_bad(c.name, c.text);
    EXPECT_EQ(bad.run.exit_code, 2) << bad.run.out;
    EXPECT_NE(bad.run.out.find(c.place), std::string::npos) << bad.run.out;
    EXPECT_FALSE(fs::exists(bad.calibrated));
    EXPECT_FALSE(fs::exists(bad.out));
  }
  // Another unit: refused at its header line.
  std::string inches = example;
  inches.replace(inches.find("# units: mm"), 11, "# units: in");
  int units_line = 1;
  for (std::size_t i = 0; i < inches.find("# units: in"); ++i) units_line += inches[i] == '\n' ? 1 : 0;
  const CalcliBadRun bad = calcli_identify_bad("units", inches);
  EXPECT_EQ(bad.run.exit_code, 2) << bad.run.out;
  EXPECT_NE(bad.run.out.find(fmt::format("m.csv:{}:10: units:", units_line)), std::string::npos)
      << bad.run.out;
  EXPECT_FALSE(fs::exists(bad.calibrated));
  EXPECT_FALSE(fs::exists(bad.out));
}

TEST(CalibrateCli, TheShippedExampleIsIdentified) {
  const fs::path dir = calcli_dir("example");
  const auto run = test::run_pkm(fmt::format(
      "calibrate identify --machine {} --measurements {} --out {} --holdout 3 --json", kCalcliMachine,
      test::source_path("examples/calibration/hexapod_ch5_tracker.csv"), (dir / "calibrated.yaml").string()));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_EQ(summary["status"], "identified");
  // The held-out error falls from the perturbation's size to the measurement noise's.
  EXPECT_LT(summary["held_out"]["rms_after_mm"].get<double>(),
            0.5 * summary["held_out"]["rms_before_mm"].get<double>());
  EXPECT_TRUE(fs::exists(dir / "calibrated_identify" / "parameters.csv"));
}

}  // namespace
}  // namespace pkm
