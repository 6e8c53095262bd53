// `pkm modes` as library calls (pipeline/modes_job.hpp, modes_map_job.hpp): the job's modes are those the
// dynamics computes at the pose, its map's points those of the frequency map over the same grid; a pose out
// of reach is refused under the name the caller gives it, a plane a planar machine does not move in names the
// parameter, and a map that cannot be written names its file.
#include "pipeline/modes_job.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "dynamics/frequency_map.hpp"
#include "pipeline/modes_map_job.hpp"
#include "pipeline/plane_map_grid.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

TEST(ModesJob, GivesTheNaturalModesAtThePoseAndItsSag) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Pose pose = machine.mechanism->home();
  auto job = pipeline::run_modes_job(machine, {pose, {}});
  ASSERT_TRUE(job) << job.error().message;
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model);
  auto direct = dynamics::natural_modes(*model, pose);
  ASSERT_TRUE(direct);
  ASSERT_EQ(job->modes.count, direct->count);
  for (int i = 0; i < direct->count; ++i) EXPECT_EQ(job->modes.frequency_Hz[i], direct->frequency_Hz[i]);
  EXPECT_EQ(job->coordinates.size(), static_cast<std::size_t>(direct->count));
  EXPECT_EQ(job->static_deflection_mm, direct->equilibrium.pose.position_mm - pose.position_mm);
  EXPECT_LT(job->static_deflection_mm.z(), 0.0);  // gravity pulls the tool down
}

TEST(ModesJob, NamesAPoseOutOfReachAsTheCallerDoes) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  Pose far = machine.mechanism->home();
  far.position_mm.z() = 5000.0;
  auto named = pipeline::run_modes_job(machine, {far, "--pose far"});
  ASSERT_FALSE(named);
  EXPECT_EQ(named.error().message.rfind("--pose far: ", 0), 0u) << named.error().message;
  auto plain = pipeline::run_modes_job(machine, {far, {}});
  ASSERT_FALSE(plain);
  EXPECT_EQ(named.error().message, "--pose far: " + plain.error().message);
}

TEST(ModesMapJob, ItsPointsAreTheFrequencyMapOfTheGrid) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  dynamics::PlaneGrid grid{machine.mechanism->home(), dynamics::GridPlane::xz, 100.0, 50.0};
  const std::string out = (std::filesystem::temp_directory_path() / "pkm_modes_map_job.csv").string();
  std::filesystem::remove(out);
  auto job = pipeline::run_modes_map_job(machine, {grid, out, "out_path"});
  ASSERT_TRUE(job) << job.error().message;
  EXPECT_EQ(job->points_per_axis, 5.0);
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model);
  auto poses = dynamics::plane_grid_poses(grid, pipeline::kMaxMapGridPoints);
  ASSERT_TRUE(poses);
  const auto direct = dynamics::frequency_map(machine, *model, *poses);
  ASSERT_EQ(job->points.size(), direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(job->points[i].status, direct[i].status) << i;
    if (direct[i].status == dynamics::MapPointStatus::ok) {
      EXPECT_EQ(job->points[i].lowest_frequency_Hz, direct[i].lowest_frequency_Hz) << i;
    }
  }
  EXPECT_EQ(job->summary.points, 25);
  EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(ModesMapJob, RefusesAPlaneAPlanarMachineDoesNotMoveInAndAnUnwritableFile) {
  const Machine planar = test::machine_from_example("examples/machines/planar2.yaml");
  dynamics::PlaneGrid xz{planar.mechanism->home(), dynamics::GridPlane::xz, 20.0, 10.0};
  auto refused = pipeline::run_modes_map_job(planar, {xz, {}, "out_path"});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::bad_input);
  EXPECT_NE(refused.error().message.find("plane xz"), std::string::npos) << refused.error().message;
  const Machine ch5 = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  dynamics::PlaneGrid centre{ch5.mechanism->home(), dynamics::GridPlane::xy, 0.0, 10.0};
  const std::string nowhere =
      (std::filesystem::temp_directory_path() / "pkm_no_such_dir" / "map.csv").string();
  auto unwritten = pipeline::run_modes_map_job(ch5, {centre, nowhere, "out_path"});
  ASSERT_FALSE(unwritten);
  EXPECT_EQ(unwritten.error().message.rfind("out_path: ", 0), 0u) << unwritten.error().message;
}

}  // namespace
}  // namespace pkm
