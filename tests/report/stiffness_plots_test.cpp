// The stiffness plots of a run's report (report/stiffness_plots.hpp, docs/report-data.md): a bode.csv and a
// stiffness_map.csv written by the library (stiffness/compliance_bode.hpp, stiffness_map.hpp) come back as
// `frequency_response` (every entry's magnitude and phase per frequency) and `stiffness_map` (the grid's two
// moving axes, a value per cell, null where the point has none, every k-th cell beyond the cap); a plan's
// directory with them gets both in its report, one without them neither; malformed files are refused naming
// the file.
#include "report/stiffness_plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"
#include "dynamics/pose_grid.hpp"
#include "formats/stiffness_csv.hpp"
#include "report/report_data.hpp"
#include "stiffness/compliance_bode.hpp"
#include "stiffness/stiffness_map.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string stiffness_plots_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_stiffness_plots_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

struct StiffnessPlotsMap {
  std::vector<Pose> poses;
  std::vector<stiffness::StiffnessMapPoint> points;
};

/// The ch5 hexapod's map over the xz plane (±400 by 200 mm: the top and bottom rows leave the drives' range).
StiffnessPlotsMap stiffness_plots_map(const Machine& machine, double step_mm = 200) {
  static StiffnessParameters springs;
  springs = *stiffness::strut_stiffness_of(machine);
  dynamics::PlaneGrid grid;
  grid.centre = machine.mechanism->home();
  grid.plane = dynamics::GridPlane::xz;
  grid.half_range_mm = 400;
  grid.step_mm = step_mm;
  StiffnessPlotsMap map;
  map.poses = *dynamics::plane_grid_poses(grid, 1e6);
  map.points = *stiffness::stiffness_map(map.poses, stiffness::strut_compliance_at(machine, springs));
  return map;
}

TEST(StiffnessPlots, TheBodeCsvComesBackAsTheFrequencyResponse) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  stiffness::BodeRequest request;
  request.points = 33;
  auto data = stiffness::machine_bode(machine, machine.mechanism->home(), request);
  ASSERT_TRUE(data.ok()) << data.error().message;
  const std::string dir = stiffness_plots_dir("bode");
  const std::string path = dir + "/" + report::kBodeCsv;
  ASSERT_TRUE(formats::write_bode_csv(path, *data).ok());
  auto json = report::frequency_response_json(path);
  ASSERT_TRUE(json.ok()) << json.error().message;
  EXPECT_EQ((*json)["file"], "bode.csv");
  ASSERT_EQ((*json)["frequency_Hz"].size(), 33u);
  ASSERT_EQ((*json)["entries"].size(), data->entries.size());
  for (std::size_t e = 0; e < data->entries.size(); ++e) {
    const auto& entry = (*json)["entries"][e];
    EXPECT_EQ(entry["name"], data->entries[e].name);
    for (std::size_t k = 0; k < 33; ++k) {
      EXPECT_NEAR(entry["magnitude_um_N"][k].get<double>(), data->magnitude_um_N[e][k],
                  1e-5 * data->magnitude_um_N[e][k]);
      EXPECT_NEAR(entry["phase_deg"][k].get<double>(), data->phase_deg[e][k], 1e-2);
    }
  }
  // A magnitude without its phase is refused, naming the file.
  std::ofstream(dir + "/broken.csv") << "frequency_Hz,xx_magnitude_um_N\n10,0.01\n";
  auto broken = report::frequency_response_json(dir + "/broken.csv");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("broken.csv"), std::string::npos) << broken.error().message;
}

TEST(StiffnessPlots, TheMapCsvComesBackAsAGridOfCells) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto map = stiffness_plots_map(machine);
  const std::string dir = stiffness_plots_dir("map");
  const std::string path = dir + "/" + report::kStiffnessMapCsv;
  ASSERT_TRUE(formats::write_stiffness_map_csv(path, *machine.mechanism, map.poses, map.points).ok());
  auto json = report::stiffness_map_json(path);
  ASSERT_TRUE(json.ok()) << json.error().message;
  EXPECT_EQ((*json)["x_label"], "x_mm");
  EXPECT_EQ((*json)["y_label"], "z_mm");  // the xz plane: y stays
  ASSERT_EQ((*json)["x"].size(), 5u);
  ASSERT_EQ((*json)["y"].size(), 5u);
  int nulls = 0;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) {
      const auto& cell = (*json)["values"][j][i];
      const auto& point = map.points[i + 5 * j];  // the grid's order: x fastest
      EXPECT_EQ((*json)["x"][i].get<double>(), map.poses[i + 5 * j].position_mm.x());
      EXPECT_EQ((*json)["y"][j].get<double>(), map.poses[i + 5 * j].position_mm.z());
      if (point.status == dynamics::MapPointStatus::ok) {
        EXPECT_NEAR(cell.get<double>(), point.lowest_stiffness_N_um, 1e-5 * point.lowest_stiffness_N_um);
      } else {
        EXPECT_TRUE(cell.is_null());
        ++nulls;
      }
    }
  }
  EXPECT_GT(nulls, 0);
  // Beyond the cap every k-th cell: 41 per axis kept to 21.
  const auto fine = stiffness_plots_map(machine, 20);
  ASSERT_TRUE(formats::write_stiffness_map_csv(path, *machine.mechanism, fine.poses, fine.points).ok());
  auto capped = report::stiffness_map_json(path, 25);
  ASSERT_TRUE(capped.ok());
  EXPECT_EQ((*capped)["x"].size(), 21u);
  EXPECT_EQ((*capped)["values"].size(), 21u);
  EXPECT_EQ((*capped)["x"][1].get<double>() - (*capped)["x"][0].get<double>(), 40.0);
  // A row with a field too few is refused with its line.
  std::ofstream(dir + "/short.csv") << "x_mm,y_mm,lowest_stiffness_N_um,status\n1,2,3,ok\n1,3,ok\n";
  auto broken = report::stiffness_map_json(dir + "/short.csv");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("short.csv:3"), std::string::npos) << broken.error().message;
}

TEST(StiffnessPlots, APlansReportHasThePlotsWhenItsDirectoryHasTheFiles) {
  const std::string dir = stiffness_plots_dir("plan");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto plain = report::report_from_directory(dir);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_FALSE(plain->contains("frequency_response"));
  EXPECT_FALSE(plain->contains("stiffness_map"));
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  stiffness::BodeRequest request;
  request.points = 20;
  ASSERT_TRUE(formats::write_bode_csv(dir + "/bode.csv",
                                      *stiffness::machine_bode(machine, machine.mechanism->home(), request))
                  .ok());
  const auto map = stiffness_plots_map(machine);
  ASSERT_TRUE(
      formats::write_stiffness_map_csv(dir + "/stiffness_map.csv", *machine.mechanism, map.poses, map.points)
          .ok());
  auto with = report::report_from_directory(dir);
  ASSERT_TRUE(with.ok()) << with.error().message;
  ASSERT_TRUE(with->contains("frequency_response"));
  EXPECT_EQ((*with)["frequency_response"]["frequency_Hz"].size(), 20u);
  ASSERT_TRUE(with->contains("stiffness_map"));
  EXPECT_EQ((*with)["stiffness_map"]["values"].size(), 5u);
  EXPECT_EQ((*with)["charts"], (*plain)["charts"]);  // the time charts are as they were
}

}  // namespace
}  // namespace pkm
