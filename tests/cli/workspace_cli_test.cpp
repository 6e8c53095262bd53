// pkm workspace: the workspace map as DIR/workspace.csv and DIR/summary.json (and the report), on the shipped
// machines. The files are there with a row per cell and the summary's counts; a glide's map marks its
// carriage limits; bad flags exit 2 with a message naming the flag and leave no output directory behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string ws_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

// A fresh output directory path in the temporary directory (nothing there yet).
std::string ws_cli_out(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("pkm_workspace_cli_" + name);
  fs::remove_all(path);
  return path.string();
}

std::vector<std::vector<std::string>> ws_cli_rows(const std::string& path, std::string& header) {
  test::CsvRows csv = test::read_csv_rows(path);
  header = csv.header;
  return std::move(csv.rows);
}

TEST(WorkspaceCli, WritesTheMapAndItsSummaryWithARowPerCell) {
  const std::string out = ws_cli_out("ch5");
  const auto run = test::run_pkm("workspace --machine " + ws_cli_machine("hexapod_ch5.yaml") +
                                     " --plane xz --range-mm 400 --step-mm 100 --out " + out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto printed = nlohmann::json::parse(run.out);
  std::ifstream summary_file(out + "/summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["kind"], "workspace");
  EXPECT_EQ(printed["cells"], summary["cells"]);
  EXPECT_EQ(printed["out"], out);
  std::string header;
  const auto rows = ws_cli_rows(out + "/workspace.csv", header);
  EXPECT_EQ(
      header,
      "x_mm,y_mm,z_mm,psi_deg,theta_deg,gamma_deg,status,limit,det_sign,condition_number,delta_rho,S_x,S_y,"
      "S_z");
  ASSERT_EQ(rows.size(), 81u);  // 9 × 9
  EXPECT_EQ(summary["cells"].get<long>(), 81);
  // x fastest, then z; the centre (home) is row 40.
  EXPECT_EQ(rows[0][0], "-400.000000");
  EXPECT_EQ(rows[0][2], "300.000000");
  EXPECT_EQ(rows[1][0], "-300.000000");
  EXPECT_EQ(rows[9][2], "400.000000");
  EXPECT_EQ(rows[40][0], "0.000000");
  EXPECT_EQ(rows[40][2], "700.000000");
  EXPECT_EQ(rows[40][6], "ok");
  EXPECT_NEAR(std::stod(rows[40][10]), 4.76, 0.005);  // Smirnov 2019, §5.2.2: δρ of the tool point at z = 700
  // The summary counts the file's statuses, and the top row is beyond actuator_max.
  std::map<std::string, long> counted;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 14u);
    ++counted[row[6]];
  }
  for (const auto& [status, n] : summary["status"].items())
    EXPECT_EQ(counted[status], n.get<long>()) << status;
  EXPECT_EQ(rows[76][6], "actuator_range");  // x = 0, z = 1100
  EXPECT_NE(rows[76][7].find("_max"), std::string::npos) << rows[76][7];
  // The summary's extremes are the ok rows'.
  double lowest = INFINITY, highest = -INFINITY;
  for (const auto& row : rows) {
    if (row[6] != "ok") continue;
    lowest = std::min(lowest, std::stod(row[10]));
    highest = std::max(highest, std::stod(row[10]));
  }
  EXPECT_NEAR(summary["layers"]["delta_rho"]["min"].get<double>(), lowest, 1e-8 * lowest);
  EXPECT_NEAR(summary["layers"]["delta_rho"]["max"].get<double>(), highest, 1e-8 * highest);
}

TEST(WorkspaceCli, PrintsTheSummaryAndWritesTheReport) {
  const std::string out = ws_cli_out("report");
  const std::string page = out + "/page.html";
  const auto run =
      test::run_pkm("workspace --machine " + ws_cli_machine("hexapod_ch5.yaml") +
                    " --range-mm 100 --step-mm 50 --stiffness --out " + out + " --report " + page);
#if PKM_REPORT_PAGE
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_TRUE(fs::exists(page));
  std::ifstream in(page);
  std::stringstream html;
  html << in.rdbuf();
  EXPECT_NE(html.str().find("\"workspace_map\""), std::string::npos);
  EXPECT_NE(run.out.find("25 cells (5 × 5): 25 ok"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("error amplification δρ"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("lowest translational stiffness"), std::string::npos) << run.out;
  // pkm report DIR gives the same page's data again.
  const auto again = test::run_pkm("report " + out + " --out " + out + "/again.html");
  EXPECT_EQ(again.exit_code, 0) << again.out;
#else
  EXPECT_NE(run.exit_code, 0) << run.out;
  EXPECT_FALSE(fs::exists(out)) << "a failed run left its directory";
#endif
}

TEST(WorkspaceCli, AGlidesWorkingZoneEndsAtItsCarriageTravel) {
  const std::string out = ws_cli_out("triglide");
  const auto run = test::run_pkm("workspace --machine " + ws_cli_machine("triglide.yaml") +
                                 " --plane xz --range-mm 600 --step-mm 50 --out " + out + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  EXPECT_GT(summary["status"]["ok"].get<long>(), 0);
  EXPECT_GT(summary["status"]["actuator_range"].get<long>(), 0);
}

TEST(WorkspaceCli, BadFlagsExitTwoAndLeaveNoDirectory) {
  const std::string out = ws_cli_out("refused");
  const std::string ch5 = "workspace --machine " + ws_cli_machine("hexapod_ch5.yaml");
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::vector<Case> cases = {
      {" --step-mm 0 --out " + out, "--step-mm"},
      {" --step-mm -5 --out " + out, "--step-mm"},
      {" --range-mm nan --out " + out, "--range-mm"},
      {" --step-mm 0.1 --out " + out, "more than 1000000; take a larger --step-mm"},
      {" --plane xw --out " + out, "--plane xw: expected xy, xz, yz or two of the coordinates"},
      {" --plane x,x --out " + out, "--plane x,x: grid axes 1 and 2 are both x"},
      {" --plane x,theta --step-deg 0 --out " + out, "--step-deg"},
      {" --grid3d --plane xy --out " + out, "--plane"},
      {" --centre 1,2,x --out " + out, "--centre"},
      {" --threads -1 --out " + out, "--threads"},
      {"", "--out"},
  };
  for (const Case& c : cases) {
    const auto run = test::run_pkm(ch5 + c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.out;
    EXPECT_NE(run.out.find(c.message), std::string::npos) << c.arguments << "\n" << run.out;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
  }
  // A machine without springs for --stiffness, a plane a planar machine cannot move in: refused before the
  // directory is made.
  const auto glide = test::run_pkm("workspace --machine " + ws_cli_machine("hexaglide.yaml") +
                                   " --frequencies --out " + out);
  EXPECT_EQ(glide.exit_code, 2) << glide.out;
  EXPECT_NE(glide.out.find("pkm workspace: error: "), std::string::npos) << glide.out;
  EXPECT_NE(glide.out.find("dynamics"), std::string::npos) << glide.out;
  const auto planar =
      test::run_pkm("workspace --machine " + ws_cli_machine("planar3.yaml") + " --plane xz --out " + out);
  EXPECT_EQ(planar.exit_code, 2) << planar.out;
  EXPECT_NE(planar.out.find("--plane xz: the planar3 does not control z"), std::string::npos) << planar.out;
  EXPECT_FALSE(fs::exists(out));
}

// pkm workspace --calibration-plan DIR: the tool error predicted after measuring the plan `pkm calibrate
// plan` wrote to DIR, a column of its own, positive and finite where the machine can stand and empty
// elsewhere; a directory that is no plan for this machine exits 2 naming the file, before any output.
std::string wscal_plan(const std::string& machine_file, const std::string& name) {
  const std::string dir = ws_cli_out("calplan_" + name);
  const auto run = test::run_pkm("calibrate plan --machine " + ws_cli_machine(machine_file) +
                                 " --method random --poses 12 --held-out 3 --box-mm 20 --out " + dir);
  EXPECT_EQ(run.exit_code, 0) << run.out;
  return dir;
}

TEST(WorkspaceCli, CalibrationPlanAddsThePredictedErrorWhereTheMachineCanStand) {
  struct Case {
    std::string machine, grid;
    bool unreachable;  ///< the grid has unreachable cells
  };
  const std::vector<Case> cases = {
      {"hexapod_ch5.yaml", " --plane xz --range-mm 400 --step-mm 100", false},
      {"triglide.yaml", " --plane xz --range-mm 600 --step-mm 100", true},
  };
  for (const Case& c : cases) {
    const std::string plan = wscal_plan(c.machine, c.machine);
    const std::string out = ws_cli_out("calibrated_" + c.machine);
    const auto run = test::run_pkm("workspace --machine " + ws_cli_machine(c.machine) + c.grid +
                                       " --calibration-plan " + plan + " --out " + out + " --json",
                                   false);
    ASSERT_EQ(run.exit_code, 0) << c.machine << "\n" << run.out;
    const auto printed = nlohmann::json::parse(run.out);
    EXPECT_EQ(printed["calibration_plan"]["poses"], 12) << c.machine;
    ASSERT_TRUE(printed["layers"].contains("calibrated_error_mm")) << c.machine;
    std::string header;
    const auto rows = ws_cli_rows(out + "/workspace.csv", header);
    const std::string column = ",calibrated_error_mm";
    ASSERT_EQ(header.rfind(column), header.size() - column.size()) << header;
    long ok = 0, stopped = 0, unreachable = 0;
    double lowest = INFINITY, highest = -INFINITY;
    for (const auto& row : rows) {
      const std::string& status = row[6];
      const std::string& value = row.back();
      if (status == "ok") {
        ++ok;
        ASSERT_FALSE(value.empty()) << c.machine;
        const double error = std::stod(value);
        EXPECT_TRUE(std::isfinite(error) && error > 0.0) << c.machine << " " << value;
        lowest = std::min(lowest, error);
        highest = std::max(highest, error);
      } else {
        ++stopped;
        unreachable += status == "unreachable";
        EXPECT_TRUE(value.empty()) << c.machine << " " << status << " " << value;
      }
    }
    EXPECT_GT(ok, 0) << c.machine;
    EXPECT_GT(stopped, 0) << c.machine;
    if (c.unreachable) {
      EXPECT_GT(unreachable, 0) << c.machine;
    }
    EXPECT_NEAR(printed["layers"]["calibrated_error_mm"]["min"].get<double>(), lowest, 1e-8 * lowest);
    EXPECT_NEAR(printed["layers"]["calibrated_error_mm"]["max"].get<double>(), highest, 1e-8 * highest);
  }
}

TEST(WorkspaceCli, CalibrationPlanThatIsNoneOrAnotherMachinesExitsTwo) {
  const std::string out = ws_cli_out("calibration_refused");
  const std::string ch5 = "workspace --machine " + ws_cli_machine("hexapod_ch5.yaml") + " --out " + out;
  const std::string none = ws_cli_out("calplan_none");
  const auto missing = test::run_pkm(ch5 + " --calibration-plan " + none);
  EXPECT_EQ(missing.exit_code, 2) << missing.out;
  EXPECT_NE(missing.out.find("pkm workspace: error: " + none + ": "), std::string::npos) << missing.out;
  EXPECT_FALSE(fs::exists(out));
  const std::string tripod_plan = wscal_plan("tripod.yaml", "tripod");
  const auto other = test::run_pkm(ch5 + " --calibration-plan " + tripod_plan);
  EXPECT_EQ(other.exit_code, 2) << other.out;
  EXPECT_NE(other.out.find(tripod_plan + "/plan.csv:1:"), std::string::npos) << other.out;
  EXPECT_NE(other.out.find("the plan has 3 actuator columns, the hexapod has 6 actuators"), std::string::npos)
      << other.out;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace pkm
