// pkm simulate on planned runs of the shipped ch5 hexapod: the summary and its files beside the plan, the
// CSV holding what the summary says; the error's parts: none for the drives when they are ideal, the drives'
// friction largest just after a drive reverses, the load's only under a load; machines the simulation cannot
// take and bad loads exit 2 naming why and write nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "report/report_data.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string simulate_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

// Two circles of 30 mm at 50 mm/s planned into `dir`/plan (every drive reverses on them).
std::string simulate_cli_circle_plan(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "circle.ngc") << "G21 G90 G17 G94\nG0 X30 Y0 Z0\nG3 X30 Y0 I-30 J0 F3000\n"
                                       "G3 X30 Y0 I-30 J0\nM2\n";
  const std::string plan = (dir / "plan").string();
  const auto planned =
      test::run_pkm("plan " + (dir / "circle.ngc").string() + " --machine " +
                    simulate_cli_machine("hexapod_ch5.yaml") + " --tables csv --out " + plan);
  EXPECT_EQ(planned.exit_code, 0) << planned.out;
  return plan;
}

// The ch5 hexapod's file with `keys` added to its drives.
std::string simulate_cli_machine_with(const std::string& name, const std::string& keys) {
  std::ifstream in(simulate_cli_machine("hexapod_ch5.yaml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("  drives: {current_time_constant_ms");
  EXPECT_NE(at, std::string::npos);
  text.insert(text.find('}', at), ", " + keys);
  const fs::path path = fs::temp_directory_path() / ("pkm_simulate_cli_" + name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

// A CSV file's columns by name, every row.
struct SimulateCsv {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  }
};

SimulateCsv read_simulate_csv(const fs::path& path) {
  SimulateCsv csv;
  std::ifstream in(path);
  std::string line, cell;
  std::getline(in, line);
  std::stringstream header(line);
  while (std::getline(header, cell, ',')) csv.names.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    while (std::getline(row, cell, ',')) values.push_back(cell.empty() ? std::nan("") : std::stod(cell));
    csv.rows.push_back(values);
  }
  return csv;
}

TEST(SimulateCli, TheSummaryTheFilesAndTheCsvAgree) {
  const std::string plan = simulate_cli_circle_plan(fs::temp_directory_path() / "pkm_simulate_cli_summary");
  const auto run =
      test::run_pkm("simulate " + plan + " --machine " + simulate_cli_machine("hexapod_ch5.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("contour error   max"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("elastic"), std::string::npos) << run.out;
  for (const char* file : {"simulate.csv", "simulate_summary.json", "simulate.svg"})
    EXPECT_TRUE(fs::exists(fs::path(plan) / file)) << file;
  std::ifstream in(fs::path(plan) / "simulate_summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["kind"], "simulate");
  const SimulateCsv csv = read_simulate_csv(fs::path(plan) / "simulate.csv");
  ASSERT_EQ(static_cast<long>(csv.rows.size()), summary["ticks"].get<long>());
  // The largest of each column is the summary's figure; the ideal drives add nothing.
  for (const auto& [column, figure] :
       {std::pair<std::string, nlohmann::json>{"contour_error_mm", summary["contour_error"]},
        {"servo_mm", summary["parts"]["servo"]},
        {"elastic_mm", summary["parts"]["elastic"]},
        {"drives_mm", summary["parts"]["drives"]}}) {
    double largest = 0.0;
    for (const auto& row : csv.rows) largest = std::max(largest, row[csv.column(column)]);
    EXPECT_NEAR(largest, figure["max_mm"].get<double>(), 1e-4 * largest + 1e-12) << column;
  }
  EXPECT_EQ(summary["parts"]["drives"]["max_mm"].get<double>(), 0.0);
  EXPECT_EQ(summary["parts"]["load"]["max_mm"].get<double>(), 0.0);
  EXPECT_GT(summary["parts"]["servo"]["max_mm"].get<double>(), 0.0);
  EXPECT_GT(summary["parts"]["elastic"]["max_mm"].get<double>(), 0.0);
  // The tool's actual path is near the commanded one: within the largest contour error plus the lag.
  const double largest = summary["contour_error"]["max_mm"].get<double>();
  EXPECT_LT(largest, 0.1);
}

// The drives' friction: their part of the error peaks within a few milliseconds after some drive reverses
// (the quadrant glitch), and a load adds the load's part.
TEST(SimulateCli, FrictionPeaksWhereADriveReversesAndALoadHasItsPart) {
  const fs::path dir = fs::temp_directory_path() / "pkm_simulate_cli_friction";
  const std::string plan = simulate_cli_circle_plan(dir);
  const std::string machine = simulate_cli_machine_with(
      "friction", "friction_coulomb_N: 60, friction_static_N: 80, stribeck_speed_mm_s: 1");
  const auto run = test::run_pkm("simulate " + plan + " --machine " + machine +
                                     " --load tangential=300 --out " + (dir / "sim").string() + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_GT(summary["parts"]["drives"]["max_mm"].get<double>(), 0.002);
  EXPECT_GT(summary["parts"]["load"]["max_mm"].get<double>(), 0.0);
  // The drives' reversals from the planned set points.
  const SimulateCsv actuators = read_simulate_csv(fs::path(plan) / "actuators.csv");
  std::vector<double> reversals_s;
  for (int j = 1; j <= 6; ++j) {
    const std::size_t q = actuators.column("q" + std::to_string(j) + "_mm");
    ASSERT_LT(q, actuators.names.size());
    for (std::size_t k = 2; k < actuators.rows.size(); ++k) {
      const double before = actuators.rows[k - 1][q] - actuators.rows[k - 2][q];
      const double after = actuators.rows[k][q] - actuators.rows[k - 1][q];
      if (before * after < 0.0) reversals_s.push_back(actuators.rows[k][actuators.column("time_s")]);
    }
  }
  ASSERT_GE(reversals_s.size(), 6u);
  // On the circles (lines 3 and 4), away from their start and their stop: starting from rest and stopping
  // are friction's events too, but no reversal.
  const SimulateCsv simulated = read_simulate_csv(dir / "sim" / "simulate.csv");
  double first_s = 1e9, last_s = 0.0;
  for (const auto& row : simulated.rows) {
    const int line = static_cast<int>(row[simulated.column("line")]);
    if (line == 3 || line == 4) {
      first_s = std::min(first_s, row[simulated.column("time_s")]);
      last_s = std::max(last_s, row[simulated.column("time_s")]);
    }
  }
  double peak_s = 0.0, peak_mm = 0.0;
  for (const auto& row : simulated.rows) {
    const double t = row[simulated.column("time_s")];
    if (t > first_s + 0.2 && t < last_s - 0.5 && row[simulated.column("drives_mm")] > peak_mm) {
      peak_mm = row[simulated.column("drives_mm")];
      peak_s = row[simulated.column("time_s")];
    }
  }
  double nearest = 1e9;
  for (double t : reversals_s)
    if (peak_s >= t) nearest = std::min(nearest, peak_s - t);
  EXPECT_LT(nearest, 0.03) << "the drives' part peaks at " << peak_s << " s";
}

// The plan's report after `pkm simulate`: the contour error with its parts and the actual point less the
// commanded one over time, their peaks those of simulate.csv, and the summary's rows in the table.
TEST(SimulateCli, ThePlansReportShowsTheSimulation) {
  const std::string plan = simulate_cli_circle_plan(fs::temp_directory_path() / "pkm_simulate_cli_report");
  const auto run = test::run_pkm("simulate " + plan + " --machine " +
                                 simulate_cli_machine("hexapod_ch5.yaml") + " --load tangential=200");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto report = report::report_from_directory(plan);
  ASSERT_TRUE(report) << report.error().message;
  const SimulateCsv csv = read_simulate_csv(fs::path(plan) / "simulate.csv");
  std::ifstream in(fs::path(plan) / "simulate_summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  const nlohmann::json* contour = nullptr;
  const nlohmann::json* deviation = nullptr;
  for (const auto& chart : (*report)["charts"]) {
    if (chart["id"] == "simulate_contour_error") contour = &chart;
    if (chart["id"] == "simulate_deviation") deviation = &chart;
  }
  ASSERT_NE(contour, nullptr);
  ASSERT_NE(deviation, nullptr);
  ASSERT_EQ((*contour)["series"].size(), 5u);
  ASSERT_EQ((*deviation)["series"].size(), 3u);
  double chart_peak = 0.0;
  for (const auto& v : (*contour)["series"][0]["values"])
    if (v.is_number()) chart_peak = std::max(chart_peak, v.get<double>());
  EXPECT_NEAR(chart_peak, summary["contour_error"]["max_mm"].get<double>(), 1e-4 * chart_peak);
  // The deviation's x: the actual x less the commanded x of the file.
  double file_x = 0.0, chart_x = 0.0;
  for (const auto& row : csv.rows)
    file_x = std::max(file_x, std::abs(row[csv.column("x_actual_mm")] - row[csv.column("x_program_mm")]));
  for (const auto& v : (*deviation)["series"][0]["values"])
    if (v.is_number()) chart_x = std::max(chart_x, std::abs(v.get<double>()));
  EXPECT_NEAR(chart_x, file_x, 1e-5 + 1e-4 * file_x);
  bool row_found = false;
  for (const auto& row : (*report)["table"])
    row_found = row_found || row.dump().find("Max contour error (simulate)") != std::string::npos;
  EXPECT_TRUE(row_found);
  // --report writes that page with the simulation, also where --out puts the simulation elsewhere.
  const fs::path elsewhere = fs::temp_directory_path() / "pkm_simulate_cli_report_out";
  fs::remove_all(elsewhere);
  const auto with_page =
      test::run_pkm("simulate " + plan + " --machine " + simulate_cli_machine("hexapod_ch5.yaml") +
                    " --out " + elsewhere.string() + " --report " + (elsewhere / "report.html").string());
  ASSERT_EQ(with_page.exit_code, 0) << with_page.out;
  std::ifstream page(elsewhere / "report.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("simulate_contour_error"), std::string::npos);
  EXPECT_NE(html.find("simulate_deviation"), std::string::npos);
}

// pkm circle --elastic: the circular test on the machine in the loop. As shipped the circle stays round to
// a few µm; the drives' friction makes its reversal glitches there too; a load without --elastic is refused.
TEST(SimulateCli, TheCircleTestRunsOnTheMachineInTheLoop) {
  const fs::path root = fs::temp_directory_path() / "pkm_simulate_cli_circle";
  fs::remove_all(root);
  const auto ideal =
      test::run_pkm("circle --elastic --machine " + simulate_cli_machine("hexapod_ch5.yaml") +
                        " --radius-mm 25 --feed-mm-min 2400 --out " + (root / "ideal").string() + " --json",
                    false);
  ASSERT_EQ(ideal.exit_code, 0) << ideal.out;
  const nlohmann::json a = nlohmann::json::parse(ideal.out);
  EXPECT_EQ(a["machine_in_the_loop"], true);
  EXPECT_LT(a["circular_deviation_ccw_um"].get<double>(), 5.0);
  for (const char* file : {"circle.svg", "circle.csv", "simulate.csv", "simulate_summary.json"})
    EXPECT_TRUE(fs::exists(root / "ideal" / file)) << file;
  const std::string friction = simulate_cli_machine_with(
      "circle_friction", "friction_coulomb_N: 60, friction_static_N: 80, stribeck_speed_mm_s: 1");
  const auto rough = test::run_pkm("circle --elastic --machine " + friction +
                                       " --radius-mm 25 --feed-mm-min 2400 --load tangential=100 --out " +
                                       (root / "friction").string() + " --json",
                                   false);
  ASSERT_EQ(rough.exit_code, 0) << rough.out;
  const nlohmann::json b = nlohmann::json::parse(rough.out);
  EXPECT_GT(b["circular_deviation_ccw_um"].get<double>(), 2.0 * a["circular_deviation_ccw_um"].get<double>());
  EXPECT_GT(b["hysteresis_um"].get<double>(), a["hysteresis_um"].get<double>());
  const auto refused = test::run_pkm("circle --machine " + simulate_cli_machine("hexapod_ch5.yaml") +
                                     " --load tangential=100 --out " + (root / "refused").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("--elastic"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(root / "refused" / "circle.csv"));
}

TEST(SimulateCli, MachinesItCannotTakeAndBadLoadsAreRefusedWritingNothing) {
  const fs::path dir = fs::temp_directory_path() / "pkm_simulate_cli_refused";
  const std::string plan = simulate_cli_circle_plan(dir);
  const fs::path out = dir / "out";
  // No servo: section.
  auto refused = test::run_pkm("simulate " + plan + " --machine " + simulate_cli_machine("hexapod_ch3.yaml") +
                               " --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("servo:"), std::string::npos) << refused.out;
  // A servo section on struts without stiffness.
  const std::string rigid = simulate_cli_machine_with("rigid", "backlash_mm: 0");
  {
    std::ifstream in(rigid);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find("    stiffness_N_mm: 200000\n");
    ASSERT_NE(at, std::string::npos);
    text.erase(at, std::string("    stiffness_N_mm: 200000\n").size());
    std::ofstream(rigid) << text;
  }
  refused = test::run_pkm("simulate " + plan + " --machine " + rigid + " --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("stiffness_N_mm"), std::string::npos) << refused.out;
  // A load that does not parse.
  refused = test::run_pkm("simulate " + plan + " --machine " + simulate_cli_machine("hexapod_ch5.yaml") +
                          " --load tangental=5 --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("--load"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(out / "simulate.csv"));
  EXPECT_FALSE(fs::exists(fs::path(plan) / "simulate.csv"));
}

}  // namespace
}  // namespace pkm
