// Workspace maps of the ch5 hexapod against what the project already pins (Smirnov 2019, §5.2.2, eqs.
// 144–146; machine/conditioning_test.cpp): the cells at C (0, 0, 500) and at the tool point at z = 700, the
// range of δρ over |x|, |y| ≤ 200 mm, every cell equal to jacobian_measures at its pose, the mechanism's
// symmetries, and the map the same bit for bit on one thread or several.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>

#include "machine/conditioning.hpp"
#include "workspace/workspace_summary.hpp"
#include "workspace_support.hpp"

namespace pkm {
namespace {

using workspace::CellStatus;
using workspace::Layer;

const workspace::LayerExtremes& ws_extremes(const workspace::WorkspaceMapSummary& s, Layer layer) {
  return s.layers[static_cast<std::size_t>(layer)];
}

TEST(WorkspaceMap, PoleCellsAreTheExtractsErrorAmplification) {
  // Recomputed: outputs of C at (0, 0, 500): δρ = 5.05 with S = (3.72, 3.22, 1.12); over |x|, |y| ≤ 200 mm δρ
  // ranges from 5.05 to 5.92.
  const Machine m = test::machine_from_text(test::ws_ch5_pole_text());
  const auto grid =
      workspace::plane_section(test::ws_level_pose(0, 0, 500), dynamics::GridPlane::xy, 200, 10);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  ASSERT_EQ(map.cells.size(), 41u * 41u);
  const workspace::WorkspaceCell& centre = map.cells[41 * 20 + 20];
  EXPECT_EQ(centre.status, CellStatus::ok);
  EXPECT_NEAR(centre.error_amplification, 5.05, 0.005);
  EXPECT_NEAR(centre.sensitivity_sums.x(), 3.72, 0.005);
  EXPECT_NEAR(centre.sensitivity_sums.y(), 3.22, 0.005);
  EXPECT_NEAR(centre.sensitivity_sums.z(), 1.12, 0.005);
  // Within the machine's limits everywhere on this square, so the summary's range is the recomputed one.
  const workspace::WorkspaceMapSummary s = workspace::summarise_workspace_map(map);
  EXPECT_EQ(s.status_cells[static_cast<std::size_t>(CellStatus::ok)], 41 * 41);
  const auto& delta_rho = ws_extremes(s, Layer::error_amplification);
  EXPECT_EQ(delta_rho.cells, 41 * 41);
  EXPECT_NEAR(delta_rho.min, 5.05, 0.005);  // 5.0466 at the centre, 5.046 10 mm beside it
  EXPECT_NEAR(delta_rho.max, 5.92, 0.01);
  EXPECT_LT(delta_rho.max, 10.0);  // δρ_MAX = 10 of Smirnov 2019 (eq. 146's example)
}

TEST(WorkspaceMap, ToolPointCellsAtZ700) {
  // Recomputed: outputs of P (150 mm tool) at z = 700: δρ = 4.76 at the centre and at most 5.73.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xy, 200, 10);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  EXPECT_NEAR(map.cells[41 * 20 + 20].error_amplification, 4.76, 0.005);
  double highest = 0.0;
  for (const workspace::WorkspaceCell& cell : map.cells) {
    ASSERT_TRUE(std::isfinite(cell.error_amplification));
    highest = std::max(highest, cell.error_amplification);
  }
  EXPECT_LE(highest, 5.73 + 0.005);
  EXPECT_GT(highest, 4.76);
}

TEST(WorkspaceMap, EveryCellIsJacobianMeasuresAtItsPose) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 50);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const workspace::GridCells cells(grid, m.mechanism->convention());
  int compared = 0;
  for (long i = 0; i < cells.count(); ++i) {
    const auto measures = jacobian_measures(*m.mechanism, cells.pose(i));
    const workspace::WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    if (!measures) {
      EXPECT_TRUE(std::isnan(cell.error_amplification)) << i;
      continue;
    }
    EXPECT_EQ(cell.error_amplification, measures->error_amplification) << i;
    EXPECT_EQ(cell.sensitivity_sums, measures->sensitivity_sums) << i;
    EXPECT_EQ(cell.condition_number, measures->condition_number) << i;
    EXPECT_EQ(cell.determinant_sign, measures->determinant > 0 ? 1 : -1) << i;
    ++compared;
  }
  EXPECT_EQ(compared, 17 * 17);
}

TEST(WorkspaceMap, PoleMapHasTheMechanismsSymmetries) {
  // The ch5 hexapod's joints are symmetric under the mirror x → −x and under turns of 120° about z (base
  // joints every 60°, platform joints at 30°, 150°, 270°). S_x, S_y, S_z are sums of absolute values along
  // the base frame's axes (eq. 144), so δρ keeps the mirror (it changes only the sign of ∂x/∂L_j) but not the
  // turn, which mixes x and y inside the sums; what the turn keeps is J's singular values and |det J|, so the
  // condition number. Checked cell by cell against the cell evaluated at the mirrored or turned pose.
  const Machine m = test::machine_from_text(test::ws_ch5_pole_text());
  const auto grid =
      workspace::plane_section(test::ws_level_pose(0, 0, 500), dynamics::GridPlane::xy, 200, 20);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const workspace::GridCells cells(grid, m.mechanism->convention());
  const double turn = 2.0 * std::numbers::pi / 3.0;
  double delta_rho_turned_most = 0.0;
  for (long i = 0; i < cells.count(); ++i) {
    const workspace::WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    const Eigen::Vector3d p = cells.pose(i).position_mm;
    workspace::WorkspaceCell mirrored, turned;
    Pose completed;
    workspace::evaluate_cell_kinematics(m, test::ws_level_pose(-p.x(), p.y(), p.z()), mirrored, completed);
    workspace::evaluate_cell_kinematics(
        m,
        test::ws_level_pose(std::cos(turn) * p.x() - std::sin(turn) * p.y(),
                            std::sin(turn) * p.x() + std::cos(turn) * p.y(), p.z()),
        turned, completed);
    EXPECT_NEAR(mirrored.error_amplification, cell.error_amplification, 1e-9 * cell.error_amplification) << i;
    EXPECT_NEAR(turned.condition_number, cell.condition_number, 1e-9 * cell.condition_number) << i;
    EXPECT_EQ(turned.determinant_sign, cell.determinant_sign) << i;
    delta_rho_turned_most =
        std::max(delta_rho_turned_most, std::abs(turned.error_amplification - cell.error_amplification));
  }
  // At the centre the turn is the identity; elsewhere δρ differs measurably (this is eq. 144, not an error).
  EXPECT_GT(delta_rho_turned_most, 1e-3);
}

// Every number of a cell, NaN included, as bits.
bool ws_same_bits(const workspace::WorkspaceCell& a, const workspace::WorkspaceCell& b) {
  const auto same = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
  };
  return a.status == b.status && a.limit == b.limit && a.limit_index == b.limit_index &&
         a.determinant_sign == b.determinant_sign && same(a.condition_number, b.condition_number) &&
         same(a.error_amplification, b.error_amplification) &&
         same(a.sensitivity_sums.x(), b.sensitivity_sums.x()) &&
         same(a.sensitivity_sums.y(), b.sensitivity_sums.y()) &&
         same(a.sensitivity_sums.z(), b.sensitivity_sums.z()) &&
         same(a.lowest_stiffness_N_um, b.lowest_stiffness_N_um) &&
         same(a.lowest_frequency_Hz, b.lowest_frequency_Hz) &&
         same(a.calibrated_error_mm, b.calibrated_error_mm);
}

TEST(WorkspaceMap, ParallelMapIsTheSerialMapBitForBit) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  // The xz section crosses the actuators' limits, so every kind of cell is compared, with the stiffness
  // layer.
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 20);
  workspace::WorkspaceMapOptions options;
  options.stiffness = true;
  options.threads = 1;
  const workspace::WorkspaceMap serial = test::ws_map_of(m, grid, options);
  for (int threads : {0, 2, 3}) {
    options.threads = threads;
    const workspace::WorkspaceMap parallel = test::ws_map_of(m, grid, options);
    ASSERT_EQ(parallel.cells.size(), serial.cells.size());
    for (std::size_t i = 0; i < serial.cells.size(); ++i) {
      ASSERT_TRUE(ws_same_bits(parallel.cells[i], serial.cells[i]))
          << "cell " << i << ", " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace pkm
