// The HTML report from the command line (docs/report.md): `pkm plan --report`, `pkm interpolate --report` and
// `pkm report DIR` write one page holding the page's bundle and the run's data (docs/report-data.md), and
// that data says what the run's own files say. Bad directories exit non-zero and write no report.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"
#include "report/csv_table.hpp"
#include "report/report_assets.hpp"
#include "report/report_data.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string fresh_report_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_report_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The data object inside a report page, checking that it sits in its own script element.
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"pkm-report-data\">";
  const auto begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  if (begin == std::string::npos) return {};
  const auto start = begin + open.size();
  const auto end = html.find("</script>", start);
  EXPECT_NE(end, std::string::npos);
  return nlohmann::json::parse(html.substr(start, end - start));
}

std::vector<std::string> program_text_lines(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

const nlohmann::json* chart(const nlohmann::json& data, const std::string& id) {
  for (const auto& c : data["charts"])
    if (c["id"] == id) return &c;
  return nullptr;
}

// pkm stiffness --report: the page of the deflection along a program, its charts' peaks the summary's.
TEST(ReportCli, StiffnessReportShowsTheDeflectionAlongTheProgram) {
  const std::string out = fresh_report_dir("stiffness");
  const std::string page = out + "/report.html";
  const auto run = test::run_pkm("stiffness " + test::source_path("examples/programs/ball_end_5axis.cl") +
                                 " --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                                 " --load tangential=600,normal=150 --frequency-response --out " + out +
                                 " --report " + page);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json data = page_data(file_text(page));
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["kind"], "stiffness");
  // The Bode plot of the point with the largest error, from bode.csv.
  EXPECT_TRUE(data.contains("frequency_response"));
  const nlohmann::json summary = nlohmann::json::parse(file_text(out + "/summary.json"));
  EXPECT_EQ(data["summary"], summary);
  const nlohmann::json* normal = chart(data, "normal_deflection");
  ASSERT_NE(normal, nullptr);
  double peak = 0.0;
  for (const auto& v : (*normal)["series"][0]["values"])
    if (v.is_number()) peak = std::max(peak, std::abs(v.get<double>()));
  // The chart keeps every bucket's extremes: its peak is the summary's largest error, in µm.
  EXPECT_NEAR(peak, 1e3 * summary["max_normal_deflection_mm"].get<double>(), 1e-5 * peak);
  const nlohmann::json* forces = chart(data, "strut_forces");
  ASSERT_NE(forces, nullptr);
  EXPECT_EQ((*forces)["series"].size(), 6u);
  EXPECT_GT(data["scene"]["frames"].size(), 1u);
}

TEST(ReportCli, PlanReportHoldsTheBundleAndWhatTheRunWrote) {
  const std::string out = fresh_report_dir("plan");
  const std::string page = out + "/view/report.html";
  const std::string program = test::source_path("examples/programs/pocket.ngc");
  const auto run = test::run_pkm("plan " + program + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") +
                                 " --tables csv --out " + out + " --report " + page);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const std::string html = file_text(page);
  // Self-contained: the bundled page code is inline and nothing is fetched.
  EXPECT_NE(html.find(std::string(report::report_script().substr(0, 200))), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  const nlohmann::json data = page_data(html);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["format"], "pkm-report-1");
  EXPECT_EQ(data["kind"], "plan");
  EXPECT_EQ(data["machine"]["type"], "hexapod");
  EXPECT_EQ(data["machine"]["limits"]["speed"], 100.0);

  const nlohmann::json summary = nlohmann::json::parse(file_text(out + "/summary.json"));
  EXPECT_EQ(data["summary"], summary);
  // Charts: positions, speeds and accelerations with their limits, path speed and feed, path error.
  for (const char* id :
       {"actuator_positions", "actuator_speeds", "actuator_accels", "path_speed", "contour_error"})
    ASSERT_NE(chart(data, id), nullptr) << id;
  const nlohmann::json& speeds = *chart(data, "actuator_speeds");
  EXPECT_EQ(speeds["series"].size(), 6u);
  EXPECT_EQ(speeds["limits"].size(), 2u);
  EXPECT_EQ(speeds["x"]["time_s"].size(), speeds["series"][0]["values"].size());
  EXPECT_EQ(speeds["x"]["s_mm"].size(), speeds["series"][0]["values"].size());
  // Decimation keeps the peak: the largest plotted speed is the summary's (from the same ticks).
  double peak = 0.0;
  for (const auto& series : speeds["series"])
    for (const auto& v : series["values"])
      if (v.is_number()) peak = std::max(peak, std::abs(v.get<double>()));
  EXPECT_NEAR(peak, summary["max_actuator_speed_mm_s"].get<double>(),
              1e-3 * summary["max_actuator_speed_mm_s"].get<double>());
  const nlohmann::json& error = *chart(data, "contour_error");
  double worst = 0.0;
  for (const auto& v : error["series"][0]["values"])
    if (v.is_number()) worst = std::max(worst, v.get<double>());
  EXPECT_NEAR(worst, summary["max_path_error_mm"].get<double>(),
              1e-3 * summary["max_path_error_mm"].get<double>());

  // The animation: frames in time order from 0 to the end, six struts each, lines of the program with their
  // text.
  const nlohmann::json& frames = data["scene"]["frames"];
  const std::size_t count = frames["time_s"].size();
  ASSERT_GE(count, 100u);
  EXPECT_LE(count, 1502u);
  EXPECT_EQ(frames["line"].size(), count);
  EXPECT_EQ(frames["struts"].size(), count);
  EXPECT_EQ(frames["strut_closeness"].size(), count);
  EXPECT_DOUBLE_EQ(frames["time_s"][0].get<double>(), 0.0);
  EXPECT_NEAR(frames["time_s"][count - 1].get<double>(), summary["duration_s"].get<double>(), 1e-9);
  const auto source = program_text_lines(program);
  for (std::size_t k = 0; k < count; k += 97) {
    if (k > 0) {
      EXPECT_GT(frames["time_s"][k].get<double>(), frames["time_s"][k - 1].get<double>());
    }
    ASSERT_EQ(frames["struts"][k].size(), 6u);
    const int line = frames["line"][k].get<int>();
    ASSERT_GE(line, 1);
    ASSERT_LE(line, static_cast<int>(source.size()));
    EXPECT_EQ(data["program"]["lines"][std::to_string(line)], source[static_cast<std::size_t>(line - 1)]);
    for (const auto& c : frames["strut_closeness"][k]) {
      EXPECT_GE(c.get<double>(), 0.0);
      EXPECT_LE(c.get<double>(), 1.0);
    }
  }
  // A strut's length in the frame is its actuator value at that time (actuators.csv).
  report::CsvReader actuators;
  ASSERT_TRUE(actuators.open(out + "/actuators.csv").ok());
  std::vector<double> row;
  ASSERT_TRUE(actuators.next(row));  // t = 0, frame 0
  for (int j = 0; j < 6; ++j) {
    const auto& strut = frames["struts"][0][static_cast<std::size_t>(j)];
    const Eigen::Vector3d base(strut[0][0].get<double>(), strut[0][1].get<double>(),
                               strut[0][2].get<double>());
    const Eigen::Vector3d top(strut[1][0].get<double>(), strut[1][1].get<double>(),
                              strut[1][2].get<double>());
    EXPECT_NEAR((top - base).norm(), row[static_cast<std::size_t>(j + 1)], 1e-3) << j;
  }
  EXPECT_EQ(data["scene"]["base_polygon"].size(), 6u);
  EXPECT_GE(data["scene"]["programmed_path"].size(), 100u);
  EXPECT_EQ(data["scene"]["executed_path"].size(), data["scene"]["executed_error_mm"].size());
  // The summary table names the machine file, and the rows with a program line point into the program.
  bool machine_row = false;
  for (const auto& r : data["table"]) {
    if (r["label"] == "Machine file") {
      machine_row = r["value"].get<std::string>().find("hexapod_ch5.yaml") != std::string::npos;
    }
    if (r.contains("line")) {
      EXPECT_TRUE(data["program"]["lines"].contains(std::to_string(r["line"].get<int>())));
    }
  }
  EXPECT_TRUE(machine_row);

  // pkm report DIR builds the same page from the files alone.
  const auto again = test::run_pkm("report " + out);
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_EQ(page_data(file_text(out + "/report.html")), data);
}

TEST(ReportCli, InterpolateReportShowsTheContourErrorAgainstTheTolerance) {
  const std::string out = fresh_report_dir("interpolate");
  const std::string page = out + "/report.html";
  const auto run =
      test::run_pkm("interpolate " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                        test::source_path("examples/machines/hexapod_ch5.yaml") +
                        " --method carrier --rho-max 0.001 --json --out " + out + " --report " + page,
                    false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  const nlohmann::json data = page_data(file_text(page));
  EXPECT_EQ(data["kind"], "interpolate");
  for (const char* id : {"actuator_positions", "steps_per_period", "contour_error"})
    ASSERT_NE(chart(data, id), nullptr) << id;
  const nlohmann::json& error = *chart(data, "contour_error");
  ASSERT_EQ(error["limits"].size(), 1u);
  EXPECT_DOUBLE_EQ(error["limits"][0]["value"].get<double>(), 0.001);
  // contour.csv holds each period's largest error: its worst is the summary's.
  double worst = 0.0;
  for (const auto& v : error["series"][0]["values"])
    if (v.is_number()) worst = std::max(worst, v.get<double>());
  EXPECT_NEAR(worst, summary["max_contour_error_mm"].get<double>(),
              1e-3 * summary["max_contour_error_mm"].get<double>());
  // The naive registers exceed ρ_max on this line (Smirnov 2019, §5.2.5): the report says so, with the line.
  ASSERT_GT(summary["max_contour_error_mm"].get<double>(), 0.001);
  ASSERT_EQ(data["limits_reached"].size(), 1u);
  EXPECT_EQ(data["limits_reached"][0]["severity"], "exceeded");
  EXPECT_EQ(data["limits_reached"][0]["line"], summary["max_contour_error_line"]);
  // Frames come from FK of the drives' positions: the tool stays within the error of the programmed line.
  const nlohmann::json& frames = data["scene"]["frames"];
  ASSERT_GE(frames["time_s"].size(), 10u);
  for (const auto& tool : frames["tool"]) {
    EXPECT_NEAR(tool[0].get<double>(), 0.0, 50.01);
    EXPECT_NEAR(tool[1].get<double>(), 0.0, 0.01);
    EXPECT_NEAR(tool[2].get<double>(), 700.0, 0.01);
  }
  // The position codes are steps.csv's.
  report::CsvReader steps;
  ASSERT_TRUE(steps.open(out + "/steps.csv").ok());
  std::vector<double> row, last;
  while (steps.next(row)) last = row;
  const auto& positions = (*chart(data, "actuator_positions"))["series"][0]["values"];
  EXPECT_NEAR(positions.back().get<double>(),
              last[static_cast<std::size_t>(steps.column("position_1"))] * 0.001, 1e-9);
}

TEST(ReportCli, OptimizeReportComparesTheLawWithHoldingTheAngleConstant) {
  const std::string out = fresh_report_dir("optimize");
  fs::create_directories(out);
  const auto run = test::run_pkm("optimize " + test::source_path("examples/programs/planar_circle.ngc") +
                                     " --machine " + test::source_path("examples/machines/planar3.yaml") +
                                     " --law increment --step-mm 0.6981 --json --out " + out +
                                     "/opt.ngc --report " + out + "/report.html",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  const nlohmann::json data = page_data(file_text(out + "/report.html"));
  EXPECT_EQ(data["kind"], "optimize");
  const nlohmann::json* angles = chart(data, "free_coordinates");
  const nlohmann::json* increments = chart(data, "strut_increments");
  ASSERT_NE(angles, nullptr);
  ASSERT_NE(increments, nullptr);
  // φ held constant stays at its start; the law's φ moves within the range the summary reports.
  ASSERT_EQ((*angles)["series"].size(), 2u);
  const auto& chosen = (*angles)["series"][0]["values"];
  const auto& held = (*angles)["series"][1]["values"];
  double lo = 1e9, hi = -1e9;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    EXPECT_DOUBLE_EQ(held[k].get<double>(), held[0].get<double>());
    lo = std::min(lo, chosen[k].get<double>());
    hi = std::max(hi, chosen[k].get<double>());
  }
  EXPECT_NEAR(lo, summary["free_range_deg"][0][0].get<double>(), 1e-3);
  EXPECT_NEAR(hi, summary["free_range_deg"][0][1].get<double>(), 1e-3);
  // The per-step increments add up to the summary's sums (a short run is not decimated).
  double chosen_sum = 0.0, held_sum = 0.0;
  for (std::size_t k = 0; k < (*increments)["series"][0]["values"].size(); ++k) {
    chosen_sum += (*increments)["series"][0]["values"][k].get<double>();
    held_sum += (*increments)["series"][1]["values"][k].get<double>();
  }
  EXPECT_NEAR(chosen_sum, summary["opt_sum_mm"].get<double>(), 1e-2);
  EXPECT_NEAR(held_sum, summary["const_sum_mm"].get<double>(), 1e-2);
  EXPECT_GE(data["scene"]["frames"]["time_s"].size(), 100u);
}

TEST(ReportCli, BadDirectoriesExitNonZeroAndWriteNoReport) {
  const std::string empty = fresh_report_dir("empty");
  fs::create_directories(empty);
  auto run = test::run_pkm("report " + empty);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("summary.json"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(empty + "/report.html"));

  // A plan directory whose path.csv was cut short: the error names the files.
  const std::string out = fresh_report_dir("cut");
  ASSERT_EQ(
      test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                    test::source_path("examples/machines/hexapod_ch5.yaml") + " --tables csv --out " + out)
          .exit_code,
      0);
  const std::string text = file_text(out + "/path.csv");
  std::ofstream(out + "/path.csv") << text.substr(0, text.size() / 2) << "\n";
  run = test::run_pkm("report " + out);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("path.csv"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out + "/report.html"));

  // A summary naming a machine file that is not there: say so and how to fix it.
  std::ofstream(out + "/summary.json") << R"({"machine": "/nonexistent/m.yaml", "duration_s": 1})";
  run = test::run_pkm("report " + out);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--machine"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace pkm
