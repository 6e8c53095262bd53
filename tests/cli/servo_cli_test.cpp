// pkm servo on a planned run of the shipped ch5 hexapod (its servo: section): the printed summary and its
// JSON, the files it writes beside the plan; a machine without a servo: section, a directory that is not a
// plan and a damaged actuators.csv exit 2 naming what is wrong and write nothing; a plan whose tables are
// ticks.h5 gives the servo run of its CSV tables.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string servo_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

// The ch5 line planned into a fresh directory, its tables as CSV files (or `tables`).
std::string servo_cli_plan(const std::string& name, const std::string& tables = "csv") {
  const fs::path dir = fs::temp_directory_path() / ("pkm_servo_cli_" + name);
  fs::remove_all(dir);
  const auto planned = test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") +
                                     " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --tables " +
                                     tables + " --out " + (dir / "plan").string());
  EXPECT_EQ(planned.exit_code, 0) << planned.out;
  return (dir / "plan").string();
}

TEST(ServoCli, PrintsTheSummaryAndWritesTheFilesBesideThePlan) {
  const std::string plan = servo_cli_plan("summary");
  const auto run = test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("contour error   max"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("drive 6"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("technical_optimum"), std::string::npos) << run.out;
  for (const char* file : {"servo.csv", "servo_bode.csv", "servo_summary.json"})
    EXPECT_TRUE(fs::exists(fs::path(plan) / file)) << file;

  const auto json = test::run_pkm(
      "servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --json --decoupled", false);
  ASSERT_EQ(json.exit_code, 0) << json.out;
  const nlohmann::json summary = nlohmann::json::parse(json.out);
  EXPECT_EQ(summary["kind"], "servo");
  EXPECT_EQ(summary["coupled"], false);
  ASSERT_EQ(summary["drives"].size(), 6u);
  for (const auto& drive : summary["drives"]) {
    // The shipped drives are tuned to the technical optimum: 4.3 % and 8.1 % overshoot, continuous.
    EXPECT_NEAR(drive["speed_loop"]["continuous"]["overshoot_pct"].get<double>(), 4.32, 0.05);
    EXPECT_NEAR(drive["position_loop"]["continuous"]["overshoot_pct"].get<double>(), 8.15, 0.05);
    EXPECT_GT(drive["max_following_error"].get<double>(), 0.0);
  }
  EXPECT_GT(summary["max_contour_error_mm"].get<double>(), 0.0);
}

// The shipped ch5 hexapod's file with the drives' imperfections added to its servo: section.
std::string servo_cli_imperfect_machine(const std::string& name, const std::string& extra_keys, int delay) {
  std::ifstream in(servo_cli_machine("hexapod_ch5.yaml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string drives = "  drives: {current_time_constant_ms: 1.0";
  const std::size_t at = text.find(drives);
  EXPECT_NE(at, std::string::npos);
  const std::size_t end = text.find('}', at);
  text.insert(end, ", " + extra_keys);
  text.insert(at, "  sample_delay_periods: " + std::to_string(delay) + "\n");
  const fs::path path = fs::temp_directory_path() / ("pkm_servo_cli_" + name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

// Friction, backlash and an encoder's counts make the tool's contour error on a circle larger than the ideal
// drives'; a sampling delay the loops cannot take is refused naming the delay, and nothing is written.
TEST(ServoCli, DriveImperfectionsGrowTheContourErrorAndADelayTooLongIsRefused) {
  // Two circles of 30 mm at 50 mm/s: every drive reverses, where friction and backlash show.
  const fs::path dir = fs::temp_directory_path() / "pkm_servo_cli_circle";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "circle.ngc") << "G21 G90 G17 G94\nG0 X30 Y0 Z0\nG3 X30 Y0 I-30 J0 F3000\n"
                                       "G3 X30 Y0 I-30 J0\nM2\n";
  const std::string plan = (dir / "plan").string();
  const auto planned = test::run_pkm("plan " + (dir / "circle.ngc").string() + " --machine " +
                                     servo_cli_machine("hexapod_ch5.yaml") + " --tables csv --out " + plan);
  ASSERT_EQ(planned.exit_code, 0) << planned.out;
  const auto ideal = test::run_pkm(
      "servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --json", false);
  ASSERT_EQ(ideal.exit_code, 0) << ideal.out;
  const std::string imperfect_machine = servo_cli_imperfect_machine(
      "imperfect",
      "friction_coulomb_N: 60, friction_static_N: 80, stribeck_speed_mm_s: 1, backlash_mm: 0.003, "
      "encoder_resolution_mm: 0.0002",
      0);
  const auto imperfect =
      test::run_pkm("servo " + plan + " --machine " + imperfect_machine + " --json", false);
  ASSERT_EQ(imperfect.exit_code, 0) << imperfect.out;
  const double ideal_error = nlohmann::json::parse(ideal.out)["max_contour_error_mm"].get<double>();
  const double imperfect_error = nlohmann::json::parse(imperfect.out)["max_contour_error_mm"].get<double>();
  EXPECT_GT(imperfect_error, ideal_error + 0.001) << ideal_error << " " << imperfect_error;

  const fs::path out = fs::temp_directory_path() / "pkm_servo_cli_delayed_out";
  fs::remove_all(out);
  const std::string delayed = servo_cli_imperfect_machine("delayed", "backlash_mm: 0", 4);
  const auto refused = test::run_pkm("servo " + plan + " --machine " + delayed + " --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("unstable"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("a sample delay of 4 periods"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("servo.sample_delay_periods"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(out / "servo.csv"));
}

// pkm circle: the circular test through the drives' loops. Ideal drives keep the circle round to a fraction
// of a µm (a lag along the path does not change the radius) and the directions alike; friction and backlash
// leave the reversal glitches: a circular deviation and a hysteresis many times larger. The plot, the
// deviations and the summary join the plan's folder; bad requests write nothing.
TEST(CircleCli, TheCircularTestShowsTheDrivesImperfections) {
  const fs::path root = fs::temp_directory_path() / "pkm_circle_cli";
  fs::remove_all(root);
  const auto ideal = test::run_pkm("circle --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --out " +
                                       (root / "ideal").string() + " --json",
                                   false);
  ASSERT_EQ(ideal.exit_code, 0) << ideal.out;
  const nlohmann::json a = nlohmann::json::parse(ideal.out);
  EXPECT_EQ(a["kind"], "circle");
  EXPECT_LT(a["circular_deviation_ccw_um"].get<double>(), 1.0);
  EXPECT_LT(a["hysteresis_um"].get<double>(), 0.5);
  for (const char* file :
       {"circle.svg", "circle.csv", "circle_summary.json", "circle.ngc", "servo.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(root / "ideal" / file)) << file;

  const std::string imperfect = servo_cli_imperfect_machine(
      "circle", "friction_coulomb_N: 60, friction_static_N: 80, stribeck_speed_mm_s: 1, backlash_mm: 0.003",
      0);
  const auto run = test::run_pkm("circle --machine " + imperfect + " --out " + (root / "imperfect").string() +
                                     " --radius-mm 25 --feed-mm-min 2400 --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json b = nlohmann::json::parse(run.out);
  EXPECT_EQ(b["radius_mm"], 25.0);
  EXPECT_GT(b["circular_deviation_ccw_um"].get<double>(),
            10.0 * a["circular_deviation_ccw_um"].get<double>());
  EXPECT_GT(b["circular_deviation_cw_um"].get<double>(), 10.0 * a["circular_deviation_cw_um"].get<double>());
  EXPECT_GT(b["hysteresis_um"].get<double>(), 1.0);
  // The deviations as written: one row per measured tick, both directions, within G of each other.
  std::ifstream csv(root / "imperfect" / "circle.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "direction,angle_deg,radial_deviation_um");
  int rows = 0;
  // Angles from the plane's first axis towards its second: G3's rows turn positive, G2's negative.
  std::map<std::string, std::pair<int, int>> turns;  // direction: (steps forward, steps back)
  std::string last_direction;
  double last_angle = 0.0;
  while (std::getline(csv, line)) {
    ++rows;
    const std::string direction = line.substr(0, line.find(','));
    const double angle = std::stod(line.substr(line.find(',') + 1));
    if (direction == last_direction) {
      const double step = std::remainder(angle - last_angle, 360.0);
      (step > 0.0 ? turns[direction].first : turns[direction].second)++;
    }
    last_direction = direction, last_angle = angle;
  }
  EXPECT_GT(rows, 2 * 1500);  // a turn of 157 mm at 40 mm/s: about 3.9 s at 1 kHz, each way
  EXPECT_EQ(turns["ccw"].second, 0) << turns["ccw"].first;
  EXPECT_EQ(turns["cw"].first, 0) << turns["cw"].second;

  const auto no_servo = test::run_pkm("circle --machine " + servo_cli_machine("hexapod_ch3.yaml") +
                                      " --out " + (root / "none").string());
  EXPECT_EQ(no_servo.exit_code, 2) << no_servo.out;
  EXPECT_NE(no_servo.out.find("servo:"), std::string::npos) << no_servo.out;
  const auto zero = test::run_pkm("circle --machine " + servo_cli_machine("hexapod_ch5.yaml") +
                                  " --radius-mm 0 --out " + (root / "zero").string());
  EXPECT_EQ(zero.exit_code, 2) << zero.out;
  const auto far = test::run_pkm("circle --machine " + servo_cli_machine("hexapod_ch5.yaml") +
                                 " --radius-mm 2000 --out " + (root / "far").string());
  EXPECT_EQ(far.exit_code, 3) << far.out;
  EXPECT_NE(far.out.find("circle.ngc:3:"), std::string::npos) << far.out;  // the program's G0 to the circle
  for (const char* dir : {"none", "zero", "far"}) EXPECT_FALSE(fs::exists(root / dir / "circle.svg")) << dir;
}

TEST(ServoCli, RefusesAMachineWithoutServoAPlanlessDirectoryAndADamagedRunWritingNothing) {
  const std::string plan = servo_cli_plan("bad");
  const auto no_servo =
      test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch3.yaml"));
  EXPECT_EQ(no_servo.exit_code, 2) << no_servo.out;
  EXPECT_NE(no_servo.out.find("no servo: section"), std::string::npos) << no_servo.out;

  const fs::path empty = fs::path(plan).parent_path() / "empty";
  fs::create_directories(empty);
  const auto planless =
      test::run_pkm("servo " + empty.string() + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  EXPECT_EQ(planless.exit_code, 2) << planless.out;
  EXPECT_NE(planless.out.find("actuators.csv"), std::string::npos) << planless.out;
  EXPECT_TRUE(fs::is_empty(empty));

  // A row of actuators.csv with a word where a length should be: its file and line.
  const fs::path actuators = fs::path(plan) / "actuators.csv";
  std::ifstream in(actuators);
  std::string text, line;
  for (int row = 1; std::getline(in, line); ++row)
    text += (row == 40 ? "0.039000,abc" + line.substr(line.find(',', line.find(',') + 1)) : line) + "\n";
  in.close();
  std::ofstream(actuators) << text;
  const auto damaged = test::run_pkm("servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml"));
  EXPECT_EQ(damaged.exit_code, 2) << damaged.out;
  EXPECT_NE(damaged.out.find("actuators.csv:40"), std::string::npos) << damaged.out;
  EXPECT_FALSE(fs::exists(fs::path(plan) / "servo.csv"));
}

TEST(ServoCli, APlanOfHdf5TablesGivesTheServoRunOfItsCsvTables) {
  nlohmann::json summaries[2];
  const char* forms[2] = {"csv", "hdf5"};
  for (int k = 0; k < 2; ++k) {
    const std::string plan = servo_cli_plan(std::string("forms_") + forms[k], forms[k]);
    EXPECT_EQ(fs::exists(fs::path(plan) / "ticks.h5"), k == 1);
    const auto run = test::run_pkm(
        "servo " + plan + " --machine " + servo_cli_machine("hexapod_ch5.yaml") + " --json", false);
    ASSERT_EQ(run.exit_code, 0) << run.out;
    summaries[k] = nlohmann::json::parse(run.out);
  }
  EXPECT_EQ(summaries[1]["ticks"], summaries[0]["ticks"]);
  EXPECT_GT(summaries[0]["ticks"].get<long>(), 100);
  // The set points differ by the tables' rounding (1e-6 mm): the loops' errors by as little.
  for (const char* key : {"max_contour_error_mm", "rms_contour_error_mm"}) {
    const double csv = summaries[0][key].get<double>(), hdf5 = summaries[1][key].get<double>();
    EXPECT_GT(csv, 0.0) << key;
    EXPECT_NEAR(hdf5, csv, 1e-3 * csv + 1e-6) << key;
  }
  EXPECT_EQ(summaries[1]["max_contour_line"], summaries[0]["max_contour_line"]);
}

}  // namespace
}  // namespace pkm
