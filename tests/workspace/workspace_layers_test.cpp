// The optional layers of a workspace map: the lowest stiffness is the stiffness map's (stiffness_map.hpp),
// the lowest natural frequency the frequency map's (frequency_map.hpp), the error after calibration the
// caller's function, each only where the machine can stand; a layer asked of a machine that cannot give it is
// refused. And the summary is the cells': counts per status, extremes and where they are.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "dynamics/elastic_model.hpp"
#include "dynamics/frequency_map.hpp"
#include "stiffness/stiffness_map.hpp"
#include "workspace/workspace_summary.hpp"
#include "workspace_support.hpp"

namespace pkm {
namespace {

using workspace::CellStatus;

std::vector<Pose> ws_grid_poses(const Machine& m, const workspace::WorkspaceGrid& grid) {
  const workspace::GridCells cells(grid, m.mechanism->convention());
  std::vector<Pose> poses;
  for (long i = 0; i < cells.count(); ++i) poses.push_back(cells.pose(i));
  return poses;
}

TEST(WorkspaceLayers, StiffnessIsTheStiffnessMapsWhereTheMachineCanStand) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 50);
  workspace::WorkspaceMapOptions options;
  options.stiffness = true;
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid, options);
  EXPECT_TRUE(map.has_stiffness);
  EXPECT_FALSE(map.has_frequencies);
  auto parameters = stiffness::strut_stiffness_of(m);
  ASSERT_TRUE(parameters.ok());
  auto expected =
      stiffness::stiffness_map(ws_grid_poses(m, grid), stiffness::strut_compliance_at(m, *parameters));
  ASSERT_TRUE(expected.ok());
  int with_value = 0;
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    const workspace::WorkspaceCell& cell = map.cells[i];
    if (cell.status != CellStatus::ok) {
      EXPECT_TRUE(std::isnan(cell.lowest_stiffness_N_um)) << i;
      continue;
    }
    ASSERT_EQ((*expected)[i].status, dynamics::MapPointStatus::ok) << i;
    EXPECT_NEAR(cell.lowest_stiffness_N_um, (*expected)[i].lowest_stiffness_N_um,
                1e-9 * (*expected)[i].lowest_stiffness_N_um)
        << i;
    ++with_value;
  }
  EXPECT_GT(with_value, 50);
}

TEST(WorkspaceLayers, FrequencyIsTheFrequencyMapsWhereTheMachineCanStand) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 300, 150);
  workspace::WorkspaceMapOptions options;
  options.frequencies = true;
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid, options);
  auto model = dynamics::make_elastic_model(m);
  ASSERT_TRUE(model.ok());
  const auto expected = dynamics::frequency_map(m, *model, ws_grid_poses(m, grid));
  int with_value = 0;
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    const workspace::WorkspaceCell& cell = map.cells[i];
    if (cell.status != CellStatus::ok) {
      EXPECT_TRUE(std::isnan(cell.lowest_frequency_Hz)) << i;
      continue;
    }
    ASSERT_EQ(expected[i].status, dynamics::MapPointStatus::ok) << i;
    EXPECT_NEAR(cell.lowest_frequency_Hz, expected[i].lowest_frequency_Hz,
                1e-9 * expected[i].lowest_frequency_Hz);
    ++with_value;
  }
  EXPECT_GE(with_value, 9);
}

TEST(WorkspaceLayers, CalibratedErrorComesFromTheCallersFunction) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 100);
  workspace::WorkspaceMapOptions options;
  std::atomic<int> calls{0};
  // A stand-in for calibration's prediction: any function of the pose, called from the map's threads.
  options.calibrated_error = [&calls](const Pose& pose) {
    ++calls;
    return 1e-3 + 1e-6 * pose.position_mm.norm();
  };
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid, options);
  EXPECT_TRUE(map.has_calibrated_error);
  const workspace::GridCells cells(grid, m.mechanism->convention());
  int ok = 0;
  for (long i = 0; i < cells.count(); ++i) {
    const workspace::WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    if (cell.status != CellStatus::ok) {
      EXPECT_TRUE(std::isnan(cell.calibrated_error_mm)) << i;
      continue;
    }
    ++ok;
    EXPECT_DOUBLE_EQ(cell.calibrated_error_mm, 1e-3 + 1e-6 * cells.pose(i).position_mm.norm()) << i;
  }
  EXPECT_EQ(calls.load(), ok);
  // Without the function, no such layer.
  const workspace::WorkspaceMap plain = test::ws_map_of(m, grid);
  EXPECT_FALSE(plain.has_calibrated_error);
  for (const workspace::WorkspaceCell& cell : plain.cells) EXPECT_TRUE(std::isnan(cell.calibrated_error_mm));
}

TEST(WorkspaceLayers, LayersTheMachineCannotGiveAreRefused) {
  const Machine glide = test::machine_from_example("examples/machines/hexaglide.yaml");
  const auto grid = workspace::plane_section(glide.mechanism->home(), dynamics::GridPlane::xy, 100, 50);
  workspace::WorkspaceMapOptions options;
  options.frequencies = true;
  auto map = workspace::workspace_map(glide, grid, options);
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.error().message.find("dynamics"), std::string::npos) << map.error().message;
  options.frequencies = false;
  options.stiffness = true;
  map = workspace::workspace_map(glide, grid, options);
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.error().message.find("hexaglide.yaml"), std::string::npos) << map.error().message;
}

TEST(WorkspaceLayers, SummaryIsTheCells) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 40);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const workspace::WorkspaceMapSummary s = workspace::summarise_workspace_map(map);
  EXPECT_EQ(s.cells, 21 * 21);
  long total = 0;
  for (long n : s.status_cells) total += n;
  EXPECT_EQ(total, s.cells);
  EXPECT_GT(s.status_cells[static_cast<std::size_t>(CellStatus::ok)], 0);
  EXPECT_GT(s.status_cells[static_cast<std::size_t>(CellStatus::actuator_range)], 0);
  for (const workspace::LayerInfo& info : workspace::workspace_layers()) {
    const workspace::LayerExtremes& e = s.layers[static_cast<std::size_t>(info.layer)];
    if (info.optional) {
      EXPECT_EQ(e.cells, 0) << info.column;
      continue;
    }
    double lo = INFINITY, hi = -INFINITY;
    long cells = 0;
    for (const workspace::WorkspaceCell& cell : map.cells) {
      if (cell.status != CellStatus::ok) continue;
      const double v = workspace::layer_value(cell, info.layer);
      ++cells;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_EQ(e.cells, cells) << info.column;
    EXPECT_EQ(e.min, lo) << info.column;
    EXPECT_EQ(e.max, hi) << info.column;
    EXPECT_EQ(workspace::layer_value(map.cells[static_cast<std::size_t>(e.min_cell)], info.layer), lo);
    EXPECT_EQ(workspace::layer_value(map.cells[static_cast<std::size_t>(e.max_cell)], info.layer), hi);
  }
  EXPECT_EQ(s.determinant_positive + s.determinant_negative, s.status_cells[0]);
}

}  // namespace
}  // namespace pkm
