// The workspace map's layer "predicted error after calibration" from a plan of `pkm calibrate plan`
// (pipeline/calibration_workspace.hpp): at a held-out pose it is the plan prediction's value for that pose
// (plan_prediction.hpp), in the map's cell as in the function; the instrument is read back as planned; a
// directory that is not a plan, or a plan made for another machine, is refused naming the file.
#include "pipeline/calibration_workspace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "calibration/plan_prediction.hpp"
#include "pipeline/calibration_run.hpp"
#include "pipeline/calibration_setup.hpp"
#include "test_support.hpp"
#include "workspace/workspace_map.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string calws_test_dir(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("pkm_calibration_workspace_" + name);
  fs::remove_all(path);
  return path.string();
}

// A random plan of `poses` poses with `held_out` held-out poses, written to a fresh directory.
pipeline::CalibrationPlanJob calws_test_job(const std::string& name, int poses, int held_out) {
  pipeline::CalibrationPlanJob job;
  job.plan.method = pipeline::CalibrationPlanMethod::random;
  job.plan.poses = poses;
  job.plan.held_out = held_out;
  job.plan.seed = 7;
  job.out_directory = calws_test_dir(name);
  return job;
}

std::string calws_test_read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void calws_test_write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(CalibrationWorkspace, TheLayerIsThePlanPredictionAtItsHeldOutPoses) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const pipeline::CalibrationPlanJob job = calws_test_job("ch5", 12, 6);
  auto planned = pipeline::calibration_plan(machine, job);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  auto model = pipeline::calibration_model(machine);
  ASSERT_TRUE(model.ok());
  // The held-out poses of the run (the same seed draws the same poses).
  auto held_out = pipeline::calibration_held_out(machine, **model, job.plan);
  ASSERT_TRUE(held_out.ok());
  ASSERT_EQ(held_out->size(), planned->prediction.tool_sd_mm.size());

  auto layer = pipeline::calibration_workspace_layer(machine, job.out_directory);
  ASSERT_TRUE(layer.ok()) << layer.error().message;
  EXPECT_TRUE(layer->plan.warnings.empty()) << layer->plan.warnings.front();
  ASSERT_EQ(layer->plan.poses.size(), 12u);
  EXPECT_EQ(layer->plan.method, "random");
  // The planned poses as written (9 decimals), the same instrument: the same prediction, exactly.
  auto again = calibration::predict_plan(**model, layer->plan.poses, layer->plan.setup, *held_out);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(layer->prediction->identifiability().rank, planned->prediction.identifiability.rank);
  for (std::size_t i = 0; i < held_out->size(); ++i) {
    const double value = layer->error_at_pose((*held_out)[i]);
    ASSERT_TRUE(std::isfinite(value) && value > 0.0) << i;
    EXPECT_NEAR(value, again->tool_sd_mm[i], 1e-12 * value) << i;
    // ... and the run's own prediction, from the poses before they were rounded into plan.csv.
    EXPECT_NEAR(value, planned->prediction.tool_sd_mm[i], 1e-6 * value) << i;
  }

  // In a map: the cell at a held-out pose (the grid's centre) holds the same value; every ok cell has one.
  const Pose centre = (*held_out)[0];
  workspace::WorkspaceMapOptions options;
  options.calibrated_error = layer->error_at_pose;
  auto map = workspace::workspace_map(
      machine, workspace::plane_section(centre, dynamics::GridPlane::xy, 20, 20), options);
  ASSERT_TRUE(map.ok()) << map.error().message;
  ASSERT_TRUE(map->has_calibrated_error);
  ASSERT_EQ(map->cells.size(), 9u);
  EXPECT_EQ(map->cells[4].status, workspace::CellStatus::ok);
  EXPECT_NEAR(map->cells[4].calibrated_error_mm, again->tool_sd_mm[0], 1e-12 * again->tool_sd_mm[0]);
  for (const workspace::WorkspaceCell& cell : map->cells) {
    if (cell.status == workspace::CellStatus::ok) {
      EXPECT_GT(cell.calibrated_error_mm, 0.0);
    }
  }
}

TEST(CalibrationWorkspace, ReadsTheInstrumentBack) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  pipeline::CalibrationPlanJob plate = calws_test_job("plate", 10, 1);
  plate.instrument.plate_radius_mm = 80.0;
  plate.instrument.sigma_mm = 0.02;
  ASSERT_TRUE(pipeline::calibration_plan(machine, plate).ok());
  auto read = pipeline::read_calibration_plan(machine, plate.out_directory);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->setup.kind, calibration::MeasurementKind::targets);
  EXPECT_DOUBLE_EQ(read->setup.sigma_mm, 0.02);
  ASSERT_EQ(read->setup.fixture.size(), 3u);
  EXPECT_NEAR(read->setup.fixture[0].position_mm.norm(), 80.0, 1e-12);

  pipeline::CalibrationPlanJob ballbar = calws_test_job("ballbar", 10, 1);
  ballbar.instrument.ballbar_centre_mm = Eigen::Vector3d(10.0, -20.0, 500.0);
  ASSERT_TRUE(pipeline::calibration_plan(machine, ballbar).ok());
  read = pipeline::read_calibration_plan(machine, ballbar.out_directory);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->setup.kind, calibration::MeasurementKind::ballbar);
  EXPECT_EQ(read->setup.ballbar_centre_mm, Eigen::Vector3d(10.0, -20.0, 500.0));
  EXPECT_DOUBLE_EQ(read->setup.sigma_mm, 0.01);

  // A fixture file, as the plan names it.
  pipeline::CalibrationPlanJob fixture = calws_test_job("fixture", 10, 1);
  fs::create_directories(fixture.out_directory + "_files");
  const std::string fixture_file = fixture.out_directory + "_files/targets.csv";
  calws_test_write(fixture_file,
                   "# units: mm\n# frame: tool\ntarget,x,y,z\nA,0,90,0\nB,-80,-40,0\nC,80,-40,10\n");
  fixture.instrument.fixture_path = fixture_file;
  ASSERT_TRUE(pipeline::calibration_plan(machine, fixture).ok());
  read = pipeline::read_calibration_plan(machine, fixture.out_directory);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_EQ(read->setup.fixture.size(), 3u);
  EXPECT_EQ(read->setup.fixture[2].position_mm, Eigen::Vector3d(80.0, -40.0, 10.0));
}

TEST(CalibrationWorkspace, RefusesWhatIsNotAPlanForThisMachineNamingTheFile) {
  const Machine ch5 = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const pipeline::CalibrationPlanJob job = calws_test_job("refused", 10, 1);
  ASSERT_TRUE(pipeline::calibration_plan(ch5, job).ok());
  const std::string plan_csv = job.out_directory + "/plan.csv";
  const std::string summary_json = job.out_directory + "/summary.json";

  // No directory.
  auto missing = pipeline::calibration_workspace_layer(ch5, job.out_directory + "_none");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  EXPECT_NE(missing.error().message.find(job.out_directory + "_none"), std::string::npos);

  // Another machine type with as many actuators: the parameters differ.
  const Machine refined = test::machine_from_example("examples/machines/hexapod_refined.yaml");
  auto other_type = pipeline::calibration_workspace_layer(refined, job.out_directory);
  ASSERT_FALSE(other_type.ok());
  EXPECT_EQ(other_type.error().code, ErrorCode::bad_input);
  EXPECT_EQ(other_type.error().message.rfind(summary_json + ": parameters: ", 0), 0u)
      << other_type.error().message;
  EXPECT_NE(other_type.error().message.find("another machine type"), std::string::npos);

  // Another actuator count: the column row says so.
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  auto other_count = pipeline::calibration_workspace_layer(tripod, job.out_directory);
  ASSERT_FALSE(other_count.ok());
  EXPECT_EQ(other_count.error().code, ErrorCode::bad_input);
  EXPECT_EQ(other_count.error().message.rfind(plan_csv + ":1:", 0), 0u) << other_count.error().message;
  EXPECT_NE(other_count.error().message.find("the plan has 6 actuator columns, the tripod has 3 actuators"),
            std::string::npos)
      << other_count.error().message;

  // Malformed files.
  const std::string plan_text = calws_test_read(plan_csv);
  const std::string summary_text = calws_test_read(summary_json);
  std::string bad = plan_text;
  bad.replace(bad.find("P02,") + 4, 1, "x");
  calws_test_write(plan_csv, bad);
  auto bad_number = pipeline::calibration_workspace_layer(ch5, job.out_directory);
  ASSERT_FALSE(bad_number.ok());
  EXPECT_EQ(bad_number.error().message.rfind(plan_csv + ":3:5: x_mm: ", 0), 0u) << bad_number.error().message;
  calws_test_write(plan_csv, plan_text);

  calws_test_write(summary_json, "{\"command\": \"calibrate simulate\"}");
  auto not_a_plan = pipeline::calibration_workspace_layer(ch5, job.out_directory);
  ASSERT_FALSE(not_a_plan.ok());
  EXPECT_EQ(not_a_plan.error().message.rfind(summary_json + ": command: ", 0), 0u)
      << not_a_plan.error().message;
  calws_test_write(summary_json, "{ not json");
  auto not_json = pipeline::calibration_workspace_layer(ch5, job.out_directory);
  ASSERT_FALSE(not_json.ok());
  EXPECT_EQ(not_json.error().message.rfind(summary_json + ": not JSON", 0), 0u) << not_json.error().message;
  calws_test_write(summary_json, summary_text);
  fs::remove(plan_csv);
  auto no_plan = pipeline::calibration_workspace_layer(ch5, job.out_directory);
  ASSERT_FALSE(no_plan.ok());
  EXPECT_NE(no_plan.error().message.find(plan_csv), std::string::npos) << no_plan.error().message;
}

}  // namespace
}  // namespace pkm
