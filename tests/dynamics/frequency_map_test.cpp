// The map of the lowest natural frequency over a plane grid of poses (dynamics/pose_grid.hpp,
// dynamics/frequency_map.hpp):
//  - the grid: 2k + 1 points per axis with the centre among them, the plane's first axis fastest, offsets in
//    whole steps (±200 mm by 0.1 mm reaches ±200), and the refusals (step ≤ 0 or not a number, too many);
//  - each point's value is natural_modes' lowest frequency there, and points without one say why: beyond the
//    actuators' range, or singular;
//  - the ch5 hexapod is 3-fold symmetric about z (base joints every 60°, platform joint pairs every 120°,
//    the platform's centre of mass on the axis and its inertia isotropic), so the map at a pose and at the
//    pose turned by 120° about z agree, also for a tilted platform.
#include "dynamics/frequency_map.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/units.hpp"
#include "dynamics/pose_grid.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

/// The machine's image of a pose under a turn T about the base's z axis: a platform joint R b + p goes to
/// T (R b + p) = (T R Tᵀ)(T b) + T p, and T b is again a platform joint, so the image is the platform at T p
/// with the rotation T R Tᵀ (not T R).
Pose frequency_map_turned_about_z(const Pose& pose, double angle_deg) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(rad_from_deg(angle_deg), Eigen::Vector3d::UnitZ()).matrix();
  Pose turned;
  turned.position_mm = turn * pose.position_mm;
  turned.rotation = turn * pose.rotation * turn.transpose();
  return turned;
}

TEST(FrequencyMapGrid, HasTheCentreAndWholeStepsEachSideFirstAxisFastest) {
  dynamics::PlaneGrid grid;
  grid.centre = test::abc_pose(10, -20, 700, 5, 0, 0);
  grid.plane = dynamics::GridPlane::xz;
  grid.half_range_mm = 45.0;  // two whole steps of 20 each side; the rest of the range is not a step
  grid.step_mm = 20.0;
  EXPECT_EQ(dynamics::grid_points_per_axis(grid.half_range_mm, grid.step_mm), 5.0);
  auto poses = dynamics::plane_grid_poses(grid, 1000);
  ASSERT_TRUE(poses.ok()) << poses.error().message;
  ASSERT_EQ(poses->size(), 25u);
  const Pose& centre = (*poses)[12];
  EXPECT_EQ((centre.position_mm - grid.centre.position_mm).norm(), 0.0);
  // Index 0 is the (−2, −2) corner; x runs fastest, z second; y and the orientation are the centre's.
  EXPECT_EQ((*poses)[0].position_mm, Eigen::Vector3d(-30, -20, 660));
  EXPECT_EQ((*poses)[1].position_mm, Eigen::Vector3d(-10, -20, 660));
  EXPECT_EQ((*poses)[5].position_mm, Eigen::Vector3d(-30, -20, 680));
  EXPECT_EQ((*poses)[24].position_mm, Eigen::Vector3d(50, -20, 740));
  for (const Pose& p : *poses) EXPECT_EQ(p.rotation, grid.centre.rotation);
  // A range that is a whole number of steps in decimal keeps its last point despite binary rounding.
  EXPECT_EQ(dynamics::grid_points_per_axis(200.0, 0.1), 4001.0);
  EXPECT_EQ(dynamics::grid_points_per_axis(0.3, 0.1), 7.0);
  EXPECT_EQ(dynamics::grid_points_per_axis(0.0, 20.0), 1.0);
  // The yz plane moves y and z only.
  grid.plane = dynamics::GridPlane::yz;
  auto yz = dynamics::plane_grid_poses(grid, 1000);
  ASSERT_TRUE(yz.ok());
  EXPECT_EQ((*yz)[1].position_mm, Eigen::Vector3d(10, -40, 660));
  EXPECT_EQ(dynamics::grid_plane_axes(dynamics::GridPlane::yz), (std::array<int, 2>{1, 2}));
}

TEST(FrequencyMapGrid, RefusesABadStepOrRangeAndTooManyPoints) {
  dynamics::PlaneGrid grid;
  for (double step :
       {0.0, -5.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    grid.step_mm = step;
    auto poses = dynamics::plane_grid_poses(grid, 1e6);
    ASSERT_FALSE(poses.ok()) << step;
    EXPECT_EQ(poses.error().code, ErrorCode::bad_input);
    EXPECT_NE(poses.error().message.find("grid step"), std::string::npos) << poses.error().message;
  }
  grid.step_mm = 20.0;
  grid.half_range_mm = -1.0;
  EXPECT_FALSE(dynamics::plane_grid_poses(grid, 1e6).ok());
  // ±200 by 20: 21 × 21 = 441 points, one more than allowed.
  grid.half_range_mm = 200.0;
  auto many = dynamics::plane_grid_poses(grid, 440);
  ASSERT_FALSE(many.ok());
  EXPECT_NE(many.error().message.find("441 points, more than 440"), std::string::npos)
      << many.error().message;
  EXPECT_TRUE(dynamics::plane_grid_poses(grid, 441).ok());
  // A step so small the count overflows an int is refused, not wrapped round.
  grid.step_mm = 1e-9;
  EXPECT_FALSE(dynamics::plane_grid_poses(grid, 1e6).ok());
  EXPECT_EQ(dynamics::grid_plane_from_string("xz").value(), dynamics::GridPlane::xz);
  EXPECT_FALSE(dynamics::grid_plane_from_string("xx").ok());
}

TEST(FrequencyMap, EachPointIsTheLowestNaturalFrequencyOrSaysWhyNot) {
  Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model.ok()) << model.error().message;
  const std::vector<Pose> poses = {
      test::abc_pose(0, 0, 700, 0, 0, 0), test::abc_pose(40, -30, 650, 0, 0, 0),
      test::abc_pose(0, 0, 5000, 0, 0, 0),  // struts of ~4.3 m, above actuator_max 900 mm
      test::abc_pose(0, 0, 150, 0, 0, 0),   // the platform joints in the base plane: below actuator_min
  };
  const auto map = dynamics::frequency_map(machine, *model, poses);
  ASSERT_EQ(map.size(), poses.size());
  for (int i = 0; i < 2; ++i) {
    auto modes = dynamics::natural_modes(*model, poses[i]);
    ASSERT_TRUE(modes.ok());
    EXPECT_EQ(map[i].status, dynamics::MapPointStatus::ok);
    EXPECT_EQ(map[i].lowest_frequency_Hz, modes->frequency_Hz[0]);
  }
  EXPECT_NE(map[0].lowest_frequency_Hz, map[1].lowest_frequency_Hz);
  EXPECT_EQ(map[2].status, dynamics::MapPointStatus::out_of_range);
  EXPECT_TRUE(std::isnan(map[2].lowest_frequency_Hz));
  EXPECT_EQ(map[3].status, dynamics::MapPointStatus::out_of_range);
  // Without the range the drives could hold it, but the struts in the base plane carry nothing up.
  machine.limits.min.reset();
  machine.limits.max.reset();
  const auto unlimited = dynamics::frequency_map(machine, *model, poses);
  EXPECT_NE(unlimited[2].status, dynamics::MapPointStatus::out_of_range);
  EXPECT_EQ(unlimited[3].status, dynamics::MapPointStatus::singular);
  EXPECT_TRUE(std::isnan(unlimited[3].lowest_frequency_Hz));
  EXPECT_STREQ(dynamics::to_string(unlimited[3].status), "singular");

  const auto s = dynamics::summarise_frequency_map(map);
  EXPECT_EQ(s.points, 4);
  EXPECT_EQ(s.with_value, 2);
  EXPECT_EQ(s.out_of_range, 2);
  EXPECT_EQ(s.unreachable + s.singular, 0);
  const int low = map[0].lowest_frequency_Hz < map[1].lowest_frequency_Hz ? 0 : 1;
  EXPECT_EQ(s.lowest_index, low);
  EXPECT_EQ(s.highest_index, 1 - low);
  const auto none =
      dynamics::summarise_frequency_map({{std::nan(""), dynamics::MapPointStatus::unreachable}});
  EXPECT_EQ(none.unreachable, 1);
  EXPECT_EQ(none.lowest_index, -1);
  EXPECT_EQ(none.highest_index, -1);
}

TEST(FrequencyMap, TheCh5HexapodsMapIsThreeFoldSymmetricAboutZ) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model.ok()) << model.error().message;
  // A level and a tilted centre; ±120 mm reaches beyond the actuators' range at the corners.
  for (const Pose& centre : {test::abc_pose(0, 0, 700, 0, 0, 0), test::abc_pose(30, -20, 680, 4, -3, 10)}) {
    dynamics::PlaneGrid grid;
    grid.centre = centre;
    grid.half_range_mm = 120.0;
    grid.step_mm = 60.0;
    auto poses = dynamics::plane_grid_poses(grid, 100);
    ASSERT_TRUE(poses.ok());
    std::vector<Pose> turned;
    for (const Pose& p : *poses) turned.push_back(frequency_map_turned_about_z(p, 120.0));
    const auto map = dynamics::frequency_map(machine, *model, *poses);
    const auto turned_map = dynamics::frequency_map(machine, *model, turned);
    int with_frequency = 0;
    double lowest = INFINITY, highest = 0.0;
    for (std::size_t i = 0; i < map.size(); ++i) {
      EXPECT_EQ(map[i].status, turned_map[i].status) << i;
      if (map[i].status != dynamics::MapPointStatus::ok) continue;
      ++with_frequency;
      lowest = std::min(lowest, map[i].lowest_frequency_Hz);
      highest = std::max(highest, map[i].lowest_frequency_Hz);
      EXPECT_NEAR(turned_map[i].lowest_frequency_Hz, map[i].lowest_frequency_Hz,
                  1e-9 * map[i].lowest_frequency_Hz)
          << i;
    }
    // Not trivially: most of the grid has a frequency, and it varies over the grid.
    EXPECT_GE(with_frequency, 9);
    EXPECT_GT(highest - lowest, 1e-2 * lowest);
  }
}

}  // namespace
}  // namespace pkm
