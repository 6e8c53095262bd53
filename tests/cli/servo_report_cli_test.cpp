// pkm servo and the report (following-error and contour-error plots and a Bode plot per loop): after `pkm
// servo` the plan's report has the following error per drive and the contour error over time with servo.csv's
// ticks, each drive's loops from servo_bode.csv, and the table rows of servo_summary.json; `pkm servo
// --report` writes that page (also with --out elsewhere), and a build without the report page refuses it with
// exit 2 and writes nothing; servo files of an earlier plan go with its output set when the folder is planned
// again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "report/report_data.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string servo_report_test_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_servo_report_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string servo_report_test_machine() {
  return test::source_path("examples/machines/hexapod_ch5.yaml");
}

// `pkm plan` of a shipped program into `dir`.
void servo_report_test_plan(const std::string& dir, const std::string& program = "ch5_line.ngc") {
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/" + program) + " --machine " +
                                 servo_report_test_machine() + " --out " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.out;
}

std::string servo_report_test_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A CSV's rows as fields (empty fields kept).
std::vector<std::vector<std::string>> servo_report_test_rows(const std::string& path,
                                                             std::vector<std::string>& header) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream text(line);
    for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    if (header.empty())
      header = fields;
    else
      rows.push_back(std::move(fields));
  }
  return rows;
}

const nlohmann::json* servo_report_test_chart(const nlohmann::json& report, const std::string& id) {
  for (const auto& chart : report["charts"])
    if (chart["id"] == id) return &chart;
  return nullptr;
}

const nlohmann::json* servo_report_test_row(const nlohmann::json& report, const std::string& label) {
  for (const auto& row : report["table"])
    if (row["label"] == label) return &row;
  return nullptr;
}

// The points a chart keeps of `rows` samples (report/decimator.hpp: whole up to two per bucket, else two per
// bucket of ⌈rows / buckets⌉).
std::size_t servo_report_test_points(std::size_t rows, std::size_t buckets = 2000) {
  if (rows <= 2 * buckets) return rows;
  const std::size_t size = (rows + buckets - 1) / buckets;
  return 2 * ((rows + size - 1) / size);
}

TEST(ServoReportCli, ThePlansReportHasTheServoPlotsOfServoCsvAndServoBodeCsv) {
  const std::string dir = servo_report_test_dir("data");
  servo_report_test_plan(dir);
  const auto run = test::run_pkm("servo " + dir + " --machine " + servo_report_test_machine());
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(servo_report_test_text(dir + "/servo_summary.json"));
  auto report = report::report_from_directory(dir);
  ASSERT_TRUE(report) << report.error().message;

  // The following error: a series per drive with servo.csv's ticks (kept whole or decimated), over time and
  // path length, its peaks those of servo.csv.
  std::vector<std::string> header;
  const auto ticks = servo_report_test_rows(dir + "/servo.csv", header);
  ASSERT_EQ(ticks.size(), summary["ticks"].get<std::size_t>());
  const nlohmann::json* following = servo_report_test_chart(*report, "servo_following_error");
  ASSERT_NE(following, nullptr);
  ASSERT_EQ((*following)["series"].size(), 6u);
  EXPECT_EQ((*following)["y_unit"], "mm");
  EXPECT_EQ((*following)["x"]["time_s"].size(), servo_report_test_points(ticks.size()));
  EXPECT_EQ((*following)["x"]["s_mm"].size(), (*following)["x"]["time_s"].size());
  for (int j = 0; j < 6; ++j) {
    const auto column = static_cast<std::size_t>(
        std::find(header.begin(), header.end(), "e" + std::to_string(j + 1) + "_mm") - header.begin());
    ASSERT_LT(column, header.size());
    double file_peak = 0.0, chart_peak = 0.0;
    for (const auto& row : ticks) file_peak = std::max(file_peak, std::abs(std::stod(row[column])));
    for (const auto& v : (*following)["series"][j]["values"])
      if (v.is_number()) chart_peak = std::max(chart_peak, std::abs(v.get<double>()));
    EXPECT_NEAR(chart_peak, file_peak, 1e-5 * file_peak) << "drive " << j + 1;
    EXPECT_NEAR(file_peak, summary["drives"][j]["max_following_error"].get<double>(), 1e-3 * file_peak)
        << "drive " << j + 1;
  }
  const nlohmann::json* contour = servo_report_test_chart(*report, "servo_contour_error");
  ASSERT_NE(contour, nullptr);
  ASSERT_EQ((*contour)["series"].size(), 1u);
  EXPECT_EQ((*contour)["x"]["time_s"].size(), (*following)["x"]["time_s"].size());

  // The servo object: servo_summary.json and each drive's loops, with servo_bode.csv's frequencies and gaps.
  ASSERT_TRUE(report->contains("servo"));
  const nlohmann::json& servo = (*report)["servo"];
  EXPECT_EQ(servo["summary"], summary);
  EXPECT_NEAR(servo["nyquist_hz"].get<double>(), 0.5 / summary["loop_period_s"].get<double>(), 1e-6);
  std::vector<std::string> bode_header;
  const auto bode_rows = servo_report_test_rows(dir + "/servo_bode.csv", bode_header);
  const auto sampled_column = static_cast<std::size_t>(
      std::find(bode_header.begin(), bode_header.end(), "speed_open_sampled_db") - bode_header.begin());
  ASSERT_LT(sampled_column, bode_header.size());
  ASSERT_EQ(servo["bode"].size(), 6u);
  for (int j = 0; j < 6; ++j) {
    const nlohmann::json& b = servo["bode"][j];
    EXPECT_EQ(b["drive"], j + 1);
    std::size_t rows = 0, sampled = 0;
    for (const auto& row : bode_rows) {
      if (row[0] != std::to_string(j + 1)) continue;
      ++rows;
      if (!row[sampled_column].empty()) ++sampled;
    }
    ASSERT_EQ(b["frequency_hz"].size(), rows);
    EXPECT_GT(sampled, 0u);
    EXPECT_LT(sampled, rows);  // the sweep goes beyond the Nyquist frequency
    EXPECT_EQ(std::count_if(b["speed_open_sampled_db"].begin(), b["speed_open_sampled_db"].end(),
                            [](const nlohmann::json& v) { return v.is_number(); }),
              static_cast<long>(sampled));
    for (const char* column : {"speed_open_db", "speed_open_deg", "position_open_db", "position_open_deg",
                               "position_closed_sampled_db"})
      EXPECT_EQ(b[column].size(), rows) << column;
  }

  // The table: the contour error with its line, the lag, the largest following error with its drive and line.
  const nlohmann::json* row = servo_report_test_row(*report, "Max contour error (servo)");
  ASSERT_NE(row, nullptr);
  EXPECT_EQ((*row)["line"], summary["max_contour_line"]);
  EXPECT_NE(servo_report_test_row(*report, "Max lag (servo)"), nullptr);
  row = servo_report_test_row(*report, "Max following error");
  ASSERT_NE(row, nullptr);
  EXPECT_NE((*row)["value"].get<std::string>().find("(drive "), std::string::npos) << *row;
  EXPECT_GT((*row)["line"].get<int>(), 0);
  EXPECT_TRUE(servo_report_test_row(*report, "Servo limits (e_max, u_max)") ||
              servo_report_test_row(*report, "Servo limits, drive 1"));
  // The coupling check: the ch5 hexapod's drives are far from independent on the line (ratios ≥ 0.3).
  bool coupled = false;
  for (const auto& drive : summary["drives"])
    coupled =
        coupled || drive["max_coupling_ratio"].get<double>() >= summary["coupling_ratio_limit"].get<double>();
  row = servo_report_test_row(*report, coupled ? "Coupling ratio ≥ 0.3" : "Max coupling ratio");
  ASSERT_NE(row, nullptr);
  if (coupled) {
    EXPECT_NE((*row)["value"].get<std::string>().find(" of 6 drives, up to "), std::string::npos) << *row;
  }
  EXPECT_NE(servo_report_test_row(*report, "Smallest phase margin (sampled)"), nullptr);
  // The program line the table names is among the page's source lines.
  EXPECT_TRUE((*report)["program"]["lines"].contains(std::to_string(summary["max_contour_line"].get<int>())));
}

TEST(ServoReportCli, ServoWritesTheReportOrRefusesWithoutThePage) {
  const std::string dir = servo_report_test_dir("page");
  servo_report_test_plan(dir);
  const std::string page = dir + "/report.html";
  const auto run =
      test::run_pkm("servo " + dir + " --machine " + servo_report_test_machine() + " --report " + page);
#if PKM_REPORT_PAGE
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("; " + page), std::string::npos) << run.out;
  const std::string html = servo_report_test_text(page);
  for (const char* key : {"\"servo\":", "\"servo_following_error\"", "\"servo_contour_error\"",
                          "\"speed_open_sampled_db\"", "Max contour error (servo)"})
    EXPECT_NE(html.find(key), std::string::npos) << key;
  // pkm report DIR finds the servo files in the plan's directory.
  const auto again = test::run_pkm("report " + dir + " --out " + dir + "/again.html");
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_NE(servo_report_test_text(dir + "/again.html").find("\"servo_following_error\""), std::string::npos);
#else
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("built without the report page"), std::string::npos) << run.out;
  for (const char* file : {"report.html", "servo.csv", "servo_bode.csv", "servo_summary.json"})
    EXPECT_FALSE(fs::exists(fs::path(dir) / file)) << file;
#endif
}

TEST(ServoReportCli, WithOutElsewhereTheReportReadsTheServoFilesFromThere) {
  const std::string dir = servo_report_test_dir("plan");
  const std::string out = servo_report_test_dir("out");
  servo_report_test_plan(dir);
  const auto run = test::run_pkm("servo " + dir + " --machine " + servo_report_test_machine() + " --out " +
                                 out + " --report " + out + "/report.html");
  EXPECT_FALSE(fs::exists(fs::path(dir) / "servo_summary.json"));
#if PKM_REPORT_PAGE
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_TRUE(fs::exists(fs::path(out) / "servo.csv"));
  const std::string html = servo_report_test_text(out + "/report.html");
  EXPECT_NE(html.find("\"servo_following_error\""), std::string::npos);
  EXPECT_NE(html.find("\"bode\":"), std::string::npos);
#else
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_FALSE(fs::exists(out)) << "a failed run left its directory";
#endif
  // The library call names the servo directory the same way.
  report::ReportOptions options;
  options.servo_directory = out;
  auto report = report::report_from_directory(dir, options);
  ASSERT_TRUE(report) << report.error().message;
#if PKM_REPORT_PAGE
  EXPECT_TRUE(report->contains("servo"));
#endif
  auto plain = report::report_from_directory(dir);
  ASSERT_TRUE(plain) << plain.error().message;
  EXPECT_FALSE(plain->contains("servo"));
}

TEST(ServoReportCli, ServoFilesOfAnEarlierPlanGoWithItsSet) {
  const std::string dir = servo_report_test_dir("stale");
  servo_report_test_plan(dir);
  const auto run = test::run_pkm("servo " + dir + " --machine " + servo_report_test_machine());
  ASSERT_EQ(run.exit_code, 0) << run.out;
  ASSERT_TRUE(fs::exists(dir + "/servo_summary.json"));
  servo_report_test_plan(dir, "circle.ngc");  // another run into the same directory replaces the whole set
  for (const char* file : {"servo.csv", "servo_bode.csv", "servo_summary.json"})
    EXPECT_FALSE(fs::exists(dir + "/" + file)) << file;
  auto report = report::report_from_directory(dir);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_FALSE(report->contains("servo"));
  EXPECT_EQ(servo_report_test_chart(*report, "servo_following_error"), nullptr);
}

}  // namespace
}  // namespace pkm
