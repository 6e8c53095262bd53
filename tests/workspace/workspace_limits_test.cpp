// The status of workspace-map cells: the same verdict as the machine's own checks (check_actuator_range,
// check_joint_limits, check_conditioning_limit, in the planner's order) naming the same actuator or joint;
// cells beyond the ch5 hexapod's strut range; the glide machines' working zones bounded by their carriages'
// travel; and the grids the library refuses.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machine/conditioning.hpp"
#include "machine/joint_limits.hpp"
#include "workspace/workspace_summary.hpp"
#include "workspace_support.hpp"

namespace pkm {
namespace {

using workspace::CellLimit;
using workspace::CellStatus;

// The cell's verdict as the machine's Status-returning checks give it, with the actuator or joint their
// message names.
struct WsExpected {
  CellStatus status = CellStatus::ok;
  std::string names;  // a piece of the check's message that the cell's limit must match
};

WsExpected ws_expected_status(const Machine& m, const Pose& pose) {
  auto q = m.mechanism->inverse(pose);
  if (!q) return {CellStatus::unreachable, ""};
  if (Status s = check_actuator_range(m, *q); !s) return {CellStatus::actuator_range, s.error().message};
  if (Status s = check_joint_limits(m, pose); !s) return {CellStatus::joint_angle, s.error().message};
  if (!jacobian_measures(*m.mechanism, pose)) return {CellStatus::singular, ""};
  if (Status s = check_conditioning_limit(m, pose); !s) {
    return {s.error().code == ErrorCode::singular ? CellStatus::singular : CellStatus::conditioning, ""};
  }
  return {};
}

std::string ws_limit_words(const workspace::WorkspaceCell& cell) {
  const int n = cell.limit_index + 1;
  switch (cell.limit) {
    case CellLimit::actuator_min:
      return fmt::format("actuator {} at", n);
    case CellLimit::actuator_max:
      return fmt::format("actuator {} at", n);
    case CellLimit::base_joint:
      return fmt::format("base joint {} swings", n);
    case CellLimit::platform_joint:
      return fmt::format("platform joint {} swings", n);
    default:
      return "";
  }
}

void ws_expect_machine_checks_agree(const Machine& m, const workspace::WorkspaceGrid& grid, int& stopped) {
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const workspace::GridCells cells(grid, m.mechanism->convention());
  for (long i = 0; i < cells.count(); ++i) {
    const workspace::WorkspaceCell& cell = map.cells[static_cast<std::size_t>(i)];
    const WsExpected expected = ws_expected_status(m, cells.pose(i));
    ASSERT_EQ(cell.status, expected.status) << "cell " << i << ": " << expected.names;
    if (cell.status == CellStatus::ok) continue;
    ++stopped;
    EXPECT_NE(expected.names.find(ws_limit_words(cell)), std::string::npos) << expected.names;
    if (cell.limit == CellLimit::actuator_min) {
      EXPECT_NE(expected.names.find("below actuator_min"), std::string::npos);
    }
    if (cell.limit == CellLimit::actuator_max) {
      EXPECT_NE(expected.names.find("above actuator_max"), std::string::npos);
    }
  }
}

TEST(WorkspaceLimits, CellsAgreeWithTheMachinesOwnChecks) {
  // The xz section of the ch5 hexapod from z = 300 to 1100 mm: struts below 350 mm at the bottom, beyond 900
  // mm at the top, joints swinging far at the sides.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  int stopped = 0;
  ws_expect_machine_checks_agree(
      m, workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 25), stopped);
  EXPECT_GT(stopped, 50);
  // Tilted sections meet the joint and conditioning limits too.
  workspace::WorkspaceGrid tilted;
  tilted.centre = m.mechanism->home();
  tilted.axes = {{0, 300.0, 30.0}, {4, 0.6, 0.06}};
  ws_expect_machine_checks_agree(m, tilted, stopped);
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  workspace::WorkspaceGrid tripod_grid;
  tripod_grid.centre = tripod.mechanism->home();
  tripod_grid.axes = {{2, 400.0, 40.0}, {3, 0.8, 0.1}};
  ws_expect_machine_checks_agree(tripod, tripod_grid, stopped);
}

TEST(WorkspaceLimits, CellsBeyondTheStrutRangeNameTheirLimit) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 200);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  // 5 × 5, x fastest: the bottom row is z = 300, the top row z = 1100.
  for (int i = 0; i < 5; ++i) {
    const workspace::WorkspaceCell& bottom = map.cells[static_cast<std::size_t>(i)];
    const workspace::WorkspaceCell& top = map.cells[static_cast<std::size_t>(20 + i)];
    EXPECT_EQ(bottom.status, CellStatus::actuator_range) << i;
    EXPECT_EQ(bottom.limit, CellLimit::actuator_min) << i;
    EXPECT_EQ(top.status, CellStatus::actuator_range) << i;
    EXPECT_EQ(top.limit, CellLimit::actuator_max) << i;
    // The geometry's measures are there all the same (Figs. 161–162 ignore the limits).
    EXPECT_TRUE(std::isfinite(top.error_amplification)) << i;
  }
  EXPECT_EQ(map.cells[12].status, CellStatus::ok);  // home
  const workspace::WorkspaceMapSummary s = workspace::summarise_workspace_map(map);
  long by_actuator = 0;
  for (long n : s.actuator_range_cells) by_actuator += n;
  EXPECT_EQ(by_actuator, s.status_cells[static_cast<std::size_t>(CellStatus::actuator_range)]);
}

// From the centre along one axis of the section, both ways: the first cell that is not ok is stopped by a
// carriage's travel. The other edges of a glide's zone are where the struts cannot reach their guides
// (unreachable), so the walk goes where the carriages run: along the hexaglide's rails (x), up and down the
// triglide's inclined guides (z).
void ws_expect_zone_ends_at_carriages(const std::string& machine_file, dynamics::GridPlane plane,
                                      int walk_axis, double half_range_mm, double step_mm) {
  const Machine m = test::machine_from_example(machine_file);
  const auto grid = workspace::plane_section(m.mechanism->home(), plane, half_range_mm, step_mm);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const int n = map.points_per_axis[0];
  const int centre = n / 2;
  const auto cell_at = [&](int k) -> const workspace::WorkspaceCell& {
    const int i = walk_axis == 0 ? k : centre, j = walk_axis == 0 ? centre : k;
    return map.cells[static_cast<std::size_t>(j * n + i)];
  };
  ASSERT_EQ(cell_at(centre).status, CellStatus::ok) << machine_file;
  for (int direction : {-1, 1}) {
    int k = centre;
    while (k + direction >= 0 && k + direction < n && cell_at(k + direction).status == CellStatus::ok)
      k += direction;
    ASSERT_TRUE(k + direction >= 0 && k + direction < n)
        << machine_file << ": the zone reaches the grid's edge";
    const workspace::WorkspaceCell& edge = cell_at(k + direction);
    EXPECT_EQ(edge.status, CellStatus::actuator_range) << machine_file << " direction " << direction;
    EXPECT_TRUE(edge.limit == CellLimit::actuator_min || edge.limit == CellLimit::actuator_max);
    EXPECT_GT(std::abs(k - centre), 2) << machine_file << ": a zone of a few cells only";
  }
}

TEST(WorkspaceLimits, AGlidesWorkingZoneEndsAtItsCarriageTravel) {
  // Rusanov et al., Fig. 8: the working zone of a glide machine is the map with the carriage limits.
  ws_expect_zone_ends_at_carriages("examples/machines/hexaglide.yaml", dynamics::GridPlane::xy, 0, 1500, 50);
  ws_expect_zone_ends_at_carriages("examples/machines/triglide.yaml", dynamics::GridPlane::xz, 1, 600, 25);
}

TEST(WorkspaceLimits, RefusedGrids) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Pose home = m.mechanism->home();
  const auto refused = [&](const Mechanism& mechanism, const workspace::WorkspaceGrid& grid,
                           const std::string& text) {
    const Status s = workspace::validate_grid(mechanism, grid);
    ASSERT_FALSE(s.ok()) << text;
    EXPECT_EQ(s.error().code, ErrorCode::bad_input);
    EXPECT_NE(s.error().message.find(text), std::string::npos) << s.error().message;
    auto map = workspace::workspace_map(m, grid);
    EXPECT_FALSE(map.ok());
  };
  refused(*m.mechanism, {home, {{0, 10, 1}}}, "not 1");
  refused(*m.mechanism, {home, {{0, 10, 1}, {1, 10, 1}, {2, 10, 1}, {3, 0.1, 0.1}}}, "not 4");
  refused(*m.mechanism, {home, {{0, 10, 1}, {0, 10, 1}}}, "grid axes 1 and 2 are both x");
  refused(*m.mechanism, {home, {{0, 10, 0}, {1, 10, 1}}}, "grid step along x (mm) must be a positive number");
  refused(*m.mechanism, {home, {{0, -1, 1}, {1, 10, 1}}}, "half-range along x (mm) must be ≥ 0");
  refused(*m.mechanism, {home, {{0, 200, 0.1}, {1, 200, 0.1}}}, "more than 1000000");
  refused(*m.mechanism, {home, {{6, 1, 1}, {1, 10, 1}}}, "coordinate 6 is not one of 0…5");
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  const Status x =
      workspace::validate_grid(*tripod.mechanism, {tripod.mechanism->home(), {{0, 10, 1}, {2, 10, 1}}});
  ASSERT_FALSE(x.ok());
  EXPECT_NE(x.error().message.find("the tripod does not control x (mm)"), std::string::npos)
      << x.error().message;
}

TEST(WorkspaceLimits, AngleSectionsStepTheAngle) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  workspace::WorkspaceGrid grid;
  grid.centre = m.mechanism->home();
  grid.axes = {{0, 100.0, 50.0}, {4, 0.2, 0.1}};
  const workspace::GridCells cells(grid, m.mechanism->convention());
  ASSERT_EQ(cells.count(), 25);
  for (long i = 0; i < cells.count(); ++i) {
    const auto at = cells.indices(i);
    const PoseVector v = vector_from_pose(m.mechanism->convention(), cells.pose(i));
    EXPECT_NEAR(v[0], (at[0] - 2) * 50.0, 1e-12) << i;
    EXPECT_NEAR(v[4], (at[1] - 2) * 0.1, 1e-12) << i;
    EXPECT_NEAR(v[3], 0.0, 1e-12) << i;
    EXPECT_NEAR(v[5], 0.0, 1e-12) << i;
    EXPECT_EQ(v[2], 700.0);
  }
  // The centre cell is the centre pose itself.
  EXPECT_EQ(cells.pose(12).position_mm, grid.centre.position_mm);
  EXPECT_TRUE(cells.pose(12).rotation.isApprox(grid.centre.rotation, 1e-15));
}

}  // namespace
}  // namespace pkm
