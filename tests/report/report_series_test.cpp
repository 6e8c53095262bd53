// The report's series and warnings (docs/report-data.md): every series of a chart is named by its quantity
// with the chart's unit ("q1 [mm]", "v1 [mm/s]", "P1 [N]", "power 1 [W]", "e1 [mm]"), so that the page's
// legend tells the curves apart; the run's own warnings and a servo run's coupled drives are the report's
// `warnings`, which the page's verdict must show.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"
#include "io/machine_file.hpp"
#include "report/report_data.hpp"
#include "report/servo_plots.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

const nlohmann::json* series_report_chart(const nlohmann::json& data, const std::string& id) {
  for (const auto& c : data["charts"])
    if (c["id"] == id) return &c;
  return nullptr;
}

std::vector<std::string> series_report_names(const nlohmann::json& chart) {
  std::vector<std::string> names;
  for (const auto& s : chart["series"]) names.push_back(s["name"].get<std::string>());
  return names;
}

TEST(ReportSeries, NamesCarryTheQuantityAndItsUnit) {
  EXPECT_EQ(report::series_name("P1", "N"), "P1 [N]");
  EXPECT_EQ(report::series_name("path speed", "mm/s"), "path speed [mm/s]");
  EXPECT_EQ(report::series_name("κ", ""), "κ");
  EXPECT_EQ(report::drive_names("power ", 2), (std::vector<std::string>{"power 1", "power 2"}));
  EXPECT_EQ(report::drive_names("P", 2, " static"), (std::vector<std::string>{"P1 static", "P2 static"}));
  const nlohmann::json w = report::warning_entry("look here", 12);
  EXPECT_EQ(w["what"], "look here");
  EXPECT_EQ(w["line"], 12);
  EXPECT_FALSE(report::warning_entry("no line").contains("line"));
}

TEST(ReportSeries, APlansChartsNameEachSeriesWithItsQuantityAndUnit) {
  const std::string dir = (fs::temp_directory_path() / "pkm_report_series_plan").string();
  fs::remove_all(dir);
  const auto run =
      test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                    test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  // The run's own warnings become the report's.
  nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
  summary["warnings"].push_back("a note of the program");
  std::ofstream(dir + "/summary.json") << summary.dump(1);

  auto data = report::report_from_directory(dir);
  ASSERT_TRUE(data) << data.error().message;
  const std::vector<std::string> positions =
      series_report_names(*series_report_chart(*data, "actuator_positions"));
  ASSERT_EQ(positions.size(), 6u);
  EXPECT_EQ(positions[0], "q1 [mm]");
  EXPECT_EQ(series_report_names(*series_report_chart(*data, "actuator_speeds"))[5], "v6 [mm/s]");
  EXPECT_EQ(series_report_names(*series_report_chart(*data, "actuator_accels"))[2], "a3 [mm/s²]");
  EXPECT_EQ(series_report_names(*series_report_chart(*data, "path_speed"))[0], "path speed [mm/s]");
  for (const auto& chart : (*data)["charts"]) {
    const std::string unit = chart["y_unit"].get<std::string>();
    ASSERT_FALSE(unit.empty()) << chart["id"];
    for (const std::string& name : series_report_names(chart)) {
      EXPECT_TRUE(name.size() > unit.size() + 3 && name.ends_with(" [" + unit + "]"))
          << chart["id"] << ": " << name;
    }
  }
  ASSERT_TRUE((*data)["warnings"].is_array());
  bool noted = false;
  for (const auto& w : (*data)["warnings"]) noted = noted || w["what"] == "a note of the program";
  EXPECT_TRUE(noted) << (*data)["warnings"].dump();
}

/// A servo run of two ticks on the ch5 hexapod whose drives have the given largest coupling ratios.
std::string series_report_servo_dir(const std::string& name, const std::vector<double>& ratios) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_report_series_servo_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  nlohmann::json drives = nlohmann::json::array();
  for (std::size_t j = 0; j < ratios.size(); ++j) {
    drives.push_back({{"max_coupling_ratio", ratios[j]},
                      {"max_coupling_line", 7},
                      {"coupled_lines", ratios[j] >= 0.3 ? nlohmann::json{7, 8} : nlohmann::json::array()}});
  }
  std::ofstream(dir / report::kServoSummaryJson)
      << nlohmann::json{{"kind", "servo"}, {"coupling_ratio_limit", 0.3}, {"drives", drives}}.dump();
  std::ofstream ticks(dir / report::kServoTicksCsv);
  ticks << "time_s,contour_error_mm";
  for (std::size_t j = 1; j <= ratios.size(); ++j) ticks << ",e" << j << "_mm";
  ticks << "\n";
  for (int k = 0; k < 2; ++k) {
    ticks << k * 0.001 << ",0.001";
    for (std::size_t j = 0; j < ratios.size(); ++j) ticks << ",0.01";
    ticks << "\n";
  }
  return dir.string();
}

TEST(ReportSeries, ServoDrivesAtTheCouplingLimitAreAWarningAndTheirErrorsAreNamedE) {
  auto machine = load_machine_file(test::source_path("examples/machines/hexapod_ch5.yaml"));
  ASSERT_TRUE(machine) << machine.error().message;
  for (const bool coupled : {true, false}) {
    const std::vector<double> ratios = coupled ? std::vector<double>{0.1, 0.5, 0.2, 0.1, 0.31, 0.1}
                                               : std::vector<double>{0.1, 0.2, 0.2, 0.1, 0.29, 0.1};
    const std::string dir = series_report_servo_dir(coupled ? "coupled" : "free", ratios);
    report::ServoTrace servo;
    ASSERT_TRUE(servo.open(dir, "", nlohmann::json::object(), 6, 2, 100));
    ASSERT_TRUE(servo.active());
    ASSERT_TRUE(servo.next(0.0, 0.0));
    ASSERT_TRUE(servo.next(0.001, 0.1));
    ASSERT_TRUE(servo.finish());
    const nlohmann::json warnings = servo.warnings();
    if (coupled) {
      ASSERT_EQ(warnings.size(), 1u) << warnings.dump();
      const std::string what = warnings[0]["what"].get<std::string>();
      EXPECT_NE(what.find("coupling ratio ≥ 0.3"), std::string::npos) << what;
      EXPECT_NE(what.find("2 of 6 drives"), std::string::npos) << what;
      EXPECT_EQ(warnings[0]["line"], 7);
    } else {
      EXPECT_TRUE(warnings.empty()) << warnings.dump();
    }
    const nlohmann::json charts = servo.charts(*machine);
    ASSERT_EQ(charts.size(), 2u);
    EXPECT_EQ(series_report_names(charts[0])[0], "e1 [mm]");
    EXPECT_EQ(series_report_names(charts[1])[0], "contour error [mm]");
  }
}

}  // namespace
}  // namespace pkm
