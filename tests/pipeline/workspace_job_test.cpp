// `pkm workspace` as a library call (pipeline/workspace_job.hpp): the job's map is the workspace map of the
// grid, its summary.json the one formats gives for it, both written as one output set when a directory is
// given and nothing written when the grid is refused.
#include "pipeline/workspace_job.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "formats/workspace_output.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

std::string workspace_job_dir(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_workspace_job_" + name);
  std::filesystem::remove_all(path);
  return path.string();
}

TEST(WorkspaceJob, ItsMapIsTheWorkspaceMapOfTheGridAndItsFilesAreWritten) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  pipeline::WorkspaceJob job;
  job.grid = workspace::plane_section(machine.mechanism->home(), dynamics::GridPlane::xz, 400.0, 100.0);
  job.options.threads = 1;
  job.out_directory = workspace_job_dir("xz");
  auto result = pipeline::run_workspace_job(machine, job);
  ASSERT_TRUE(result) << result.error().message;
  auto direct = workspace::workspace_map(machine, job.grid, job.options);
  ASSERT_TRUE(direct);
  ASSERT_EQ(result->map.cells.size(), direct->cells.size());
  for (std::size_t i = 0; i < direct->cells.size(); ++i) {
    EXPECT_EQ(result->map.cells[i].status, direct->cells[i].status) << i;
    EXPECT_EQ(result->map.cells[i].determinant_sign, direct->cells[i].determinant_sign) << i;
  }
  EXPECT_EQ(result->summary_json,
            formats::workspace_summary_json(machine, *direct, workspace::summarise_workspace_map(*direct)));
  EXPECT_FALSE(result->calibration);
  EXPECT_TRUE(std::filesystem::exists(job.out_directory + "/" + formats::kWorkspaceCsv));
  EXPECT_TRUE(std::filesystem::exists(job.out_directory + "/" + formats::kWorkspaceSummaryJson));
}

TEST(WorkspaceJob, ARefusedGridLeavesNoDirectoryBehind) {
  const Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  pipeline::WorkspaceJob job;
  job.grid = workspace::plane_section(machine.mechanism->home(), dynamics::GridPlane::xz, 100.0, 50.0);
  job.out_directory = workspace_job_dir("refused");
  auto result = pipeline::run_workspace_job(machine, job);
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::bad_input);
  EXPECT_FALSE(std::filesystem::exists(job.out_directory));
}

}  // namespace
}  // namespace pkm
