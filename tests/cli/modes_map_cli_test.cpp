// pkm modes --map: the lowest natural frequency over a plane grid, as a CSV with a summary. On the shipped
// ch5 hexapod: one row per grid point, the centre's value is `pkm modes --pose` there, points beyond the
// actuators' range are marked and have no value, the summary matches the file; and the inputs it refuses
// (bad or zero step, a grid too large, --map without --out or with --pose, a machine without stiffness)
// exit 2 without touching the output file.
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

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string modes_map_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

/// A fresh path for a map in the temporary directory (nothing there yet).
std::string modes_map_out(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("pkm_modes_map_cli_" + name + ".csv");
  fs::remove(path);
  return path.string();
}

struct ModesMapCsv {
  std::string header;
  std::vector<std::vector<std::string>> rows;
};

ModesMapCsv read_modes_map_csv(const std::string& path) {
  ModesMapCsv csv;
  std::ifstream in(path);
  std::getline(in, csv.header);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream text(line);
    for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    csv.rows.push_back(fields);
  }
  return csv;
}

std::string modes_map_file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ModesMapCli, TheCh5MapHasARowPerPointAndTheCentreIsModesAtThatPose) {
  const std::string out = modes_map_out("ch5");
  const auto run = test::run_pkm("modes --machine " + modes_map_machine("hexapod_ch5.yaml") +
                                     " --map --centre 10,-20,690,0,0,0 --range-mm 100 --step-mm 50 --out " +
                                     out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  const ModesMapCsv csv = read_modes_map_csv(out);
  EXPECT_EQ(csv.header, "x_mm,y_mm,z_mm,psi_deg,theta_deg,gamma_deg,lowest_frequency_Hz,status");
  ASSERT_EQ(csv.rows.size(), 25u);  // 5 × 5
  EXPECT_EQ(summary["points"].get<int>(), 25);
  EXPECT_EQ(summary["points_per_axis"].get<int>(), 5);
  // x fastest, then y; z and the angles are the centre's.
  EXPECT_EQ(csv.rows[0][0], "-90.000000");
  EXPECT_EQ(csv.rows[0][1], "-120.000000");
  EXPECT_EQ(csv.rows[1][0], "-40.000000");
  EXPECT_EQ(csv.rows[5][1], "-70.000000");
  for (const auto& row : csv.rows) {
    ASSERT_EQ(row.size(), 8u);
    EXPECT_EQ(row[2], "690.000000");
  }
  // The centre, row 12, against the single-pose command.
  const auto& centre = csv.rows[12];
  EXPECT_EQ(centre[0], "10.000000");
  EXPECT_EQ(centre[1], "-20.000000");
  ASSERT_EQ(centre[7], "ok");
  const auto single = test::run_pkm(
      "modes --machine " + modes_map_machine("hexapod_ch5.yaml") + " --pose 10,-20,690,0,0,0 --json", false);
  ASSERT_EQ(single.exit_code, 0) << single.out;
  const double expected_Hz = nlohmann::json::parse(single.out)["frequencies_Hz"][0].get<double>();
  EXPECT_NEAR(std::stod(centre[6]), expected_Hz, 1e-6);
  // The summary is the file's: its count of values, lowest and highest.
  int with_frequency = 0;
  double lowest = INFINITY, highest = -INFINITY;
  for (const auto& row : csv.rows) {
    if (row[7] != "ok") continue;
    ++with_frequency;
    lowest = std::min(lowest, std::stod(row[6]));
    highest = std::max(highest, std::stod(row[6]));
  }
  EXPECT_EQ(summary["with_frequency"].get<int>(), with_frequency);
  EXPECT_NEAR(summary["reachable_share"].get<double>(), with_frequency / 25.0, 1e-12);
  EXPECT_NEAR(summary["min_frequency_Hz"].get<double>(), lowest, 1e-6);
  EXPECT_NEAR(summary["max_frequency_Hz"].get<double>(), highest, 1e-6);
  EXPECT_GT(highest, lowest);
  EXPECT_EQ(summary["min_pose"].size(), 6u);
}

TEST(ModesMapCli, PointsBeyondTheActuatorsRangeAreMarkedWithoutAValue) {
  // The xz plane through home, z from 300 to 1100 mm: the struts are shorter than actuator_min 350 mm at the
  // bottom and longer than actuator_max 900 mm at the top.
  const std::string out = modes_map_out("xz");
  const auto run = test::run_pkm("modes --machine " + modes_map_machine("hexapod_ch5.yaml") +
                                 " --map --plane xz --range-mm 400 --step-mm 200 --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const ModesMapCsv csv = read_modes_map_csv(out);
  ASSERT_EQ(csv.rows.size(), 25u);
  int marked = 0, with_value = 0;
  for (const auto& row : csv.rows) {
    ASSERT_EQ(row.size(), 8u);
    EXPECT_EQ(row[1], "0.000000");  // y stays the centre's
    const double z = std::stod(row[2]);
    if (z == 300.0 || z == 1100.0) {
      EXPECT_EQ(row[7], "out_of_range") << z;
    }
    if (row[7] == "ok") {
      ++with_value;
      EXPECT_GT(std::stod(row[6]), 0.0);
    } else {
      ++marked;
      EXPECT_EQ(row[6], "") << row[7];
    }
  }
  EXPECT_GE(marked, 10);
  EXPECT_GE(with_value, 1);
  EXPECT_EQ(csv.rows[12][7], "ok");  // home
  EXPECT_NE(run.out.find("25 points (5 × 5): " + std::to_string(with_value) + " with a frequency"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("lowest "), std::string::npos) << run.out;
}

TEST(ModesMapCli, ThePlanarBipedsMapHasItsTwoCoordinates) {
  const std::string out = modes_map_out("planar2");
  const auto run = test::run_pkm("modes --machine " + modes_map_machine("planar2.yaml") +
                                 " --map --centre 120,250 --range-mm 20 --step-mm 10 --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const ModesMapCsv csv = read_modes_map_csv(out);
  EXPECT_EQ(csv.header, "x_mm,y_mm,lowest_frequency_Hz,status");
  ASSERT_EQ(csv.rows.size(), 25u);
  EXPECT_EQ(csv.rows[12][0], "120.000000");
  EXPECT_EQ(csv.rows[12][3], "ok");
  const auto xz = test::run_pkm("modes --machine " + modes_map_machine("planar2.yaml") +
                                " --map --plane xz --out " + modes_map_out("planar2_xz"));
  EXPECT_EQ(xz.exit_code, 2) << xz.out;
  EXPECT_NE(xz.out.find("--plane xz: a planar machine moves in the xy plane only"), std::string::npos)
      << xz.out;
}

TEST(ModesMapCli, BadInputExitsTwoAndLeavesTheOutputAsItWas) {
  const std::string out = modes_map_out("refused");
  std::ofstream(out) << "the previous map\n";
  const std::string ch5 = "modes --machine " + modes_map_machine("hexapod_ch5.yaml");
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::vector<Case> cases = {
      {" --map --step-mm 0 --out " + out, "--step-mm"},
      {" --map --step-mm -5 --out " + out, "--step-mm"},
      {" --map --step-mm abc --out " + out, "--step-mm"},
      {" --map --range-mm nan --out " + out, "--range-mm"},
      {" --map --step-mm 0.01 --out " + out, "--step-mm 0.01 with --range-mm 200 gives 40001 × 40001"},
      {" --map --plane xw --out " + out, "--plane"},
      {" --map --centre 1,2,x --out " + out, "--centre"},
      {" --map --centre 1,2 --out " + out, "--centre"},
      {" --map", "--out"},
      {" --map --pose 0,0,700,0,0,0 --out " + out, "--pose"},
      {" --step-mm 10", "--map"},
      {"", "give --pose P (one pose), or --map --out FILE (a map)"},
  };
  for (const Case& c : cases) {
    const auto run = test::run_pkm(ch5 + c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.out;
    EXPECT_NE(run.out.find("pkm modes: error: "), std::string::npos) << c.arguments << "\n" << run.out;
    EXPECT_NE(run.out.find(c.message), std::string::npos) << c.arguments << "\n" << run.out;
  }
  // A machine without a dynamics: section is refused before any point is computed.
  const auto none =
      test::run_pkm("modes --machine " + modes_map_machine("hexaglide.yaml") + " --map --out " + out);
  EXPECT_EQ(none.exit_code, 2) << none.out;
  EXPECT_NE(none.out.find("hexaglide.yaml: the machine file has no dynamics: section"), std::string::npos)
      << none.out;
  EXPECT_EQ(modes_map_file_text(out), "the previous map\n");
  // An output that cannot be written: no such directory.
  const auto unwritable = test::run_pkm(ch5 + " --map --range-mm 0 --out " +
                                        (fs::temp_directory_path() / "pkm_no_such_dir/map.csv").string());
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.out;
  EXPECT_NE(unwritable.out.find("--out: cannot write"), std::string::npos) << unwritable.out;
}

}  // namespace
}  // namespace pkm
