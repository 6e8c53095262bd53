// `pkm compliance` as library calls (pipeline/compliance_job.hpp, compliance_map_job.hpp): the job's
// compliance is the struts' compliance at the pose, its Bode data the machine's Bode data, written as asked;
// a frequency range upside down is refused naming the parameters before any file is written, and the map's
// points are the stiffness map over the same grid.
#include "pipeline/compliance_job.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pipeline/compliance_map_job.hpp"
#include "pipeline/plane_map_grid.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

std::string compliance_job_out(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_compliance_job_" + name);
  std::filesystem::remove(path);
  return path.string();
}

TEST(ComplianceJob, GivesTheStrutComplianceAtThePoseAndWritesTheBodeData) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  pipeline::ComplianceJob job;
  job.pose = machine.mechanism->home();
  job.bode = stiffness::BodeRequest{};
  job.bode->points = 21;
  job.bode_path = compliance_job_out("bode.csv");
  auto result = pipeline::run_compliance_job(machine, job);
  ASSERT_TRUE(result) << result.error().message;
  auto parameters = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(parameters);
  auto direct = stiffness::strut_compliance(*machine.mechanism, *parameters, job.pose);
  ASSERT_TRUE(direct);
  EXPECT_EQ(result->compliance.compliance, direct->compliance);
  ASSERT_TRUE(result->bode);
  auto bode = stiffness::machine_bode(machine, job.pose, *job.bode);
  ASSERT_TRUE(bode);
  EXPECT_EQ(result->bode->frequency_Hz, bode->frequency_Hz);
  EXPECT_EQ(result->bode->magnitude_um_N, bode->magnitude_um_N);
  EXPECT_TRUE(std::filesystem::exists(job.bode_path));
}

TEST(ComplianceJob, RefusesAFrequencyRangeUpsideDownNamingItsParameters) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  pipeline::ComplianceJob job;
  job.pose = machine.mechanism->home();
  job.bode = stiffness::BodeRequest{};
  job.bode->f_min_Hz = 100.0;
  job.bode->f_max_Hz = 50.0;
  job.bode_path = compliance_job_out("refused.csv");
  auto result = pipeline::run_compliance_job(machine, job);
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::bad_input);
  EXPECT_EQ(result.error().message, "f_max_Hz 50 must be above f_min_Hz 100");
  EXPECT_FALSE(std::filesystem::exists(job.bode_path));
}

TEST(ComplianceMapJob, ItsPointsAreTheStiffnessMapOfTheGrid) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  pipeline::ComplianceMapJob job;
  job.grid = dynamics::PlaneGrid{machine.mechanism->home(), dynamics::GridPlane::xz, 300.0, 100.0};
  job.out_path = compliance_job_out("map.csv");
  auto result = pipeline::run_compliance_map_job(machine, job);
  ASSERT_TRUE(result) << result.error().message;
  auto parameters = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(parameters);
  auto poses = dynamics::plane_grid_poses(job.grid, pipeline::kMaxMapGridPoints);
  ASSERT_TRUE(poses);
  auto direct = stiffness::stiffness_map(*poses, stiffness::strut_compliance_at(machine, *parameters));
  ASSERT_TRUE(direct);
  ASSERT_EQ(result->points.size(), direct->size());
  for (std::size_t i = 0; i < direct->size(); ++i) {
    EXPECT_EQ(result->points[i].status, (*direct)[i].status) << i;
    if ((*direct)[i].status == dynamics::MapPointStatus::ok) {
      EXPECT_EQ(result->points[i].lowest_stiffness_N_um, (*direct)[i].lowest_stiffness_N_um) << i;
    }
  }
  EXPECT_GT(result->summary.out_of_range, 0);  // ±300 mm in z leaves the drives' range
  EXPECT_TRUE(std::filesystem::exists(job.out_path));
}

}  // namespace
}  // namespace pkm
