// The map of the lowest translational stiffness over a plane grid of poses (src/stiffness/stiffness_map.hpp):
//  - each cell is the single-pose computation there: the inverse of the largest eigenvalue of the
//    translational block of the strut-only compliance, its direction that eigenvector (ch5 hexapod and random
//    hexapods with random springs);
//  - cells without a value say why, as the model's error says (beyond the drives' range, out of reach,
//    singular), and an error that is not about a pose stops the map;
//  - the ch5 hexapod is mirror symmetric about the yz plane (x → −x) and 3-fold symmetric about z: the map
//    over a grid centred on the axis is mirror symmetric, and the map over turned poses equals the map;
//  - any compliance model plugs in (a model twice as compliant halves every value);
//  - the CSV holds a row per pose with empty cells where there is no value.
#include "stiffness/stiffness_map.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <sstream>

#include "core/units.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/pose_grid.hpp"
#include "formats/stiffness_csv.hpp"

namespace pkm {
namespace {

using dynamics::MapPointStatus;
using stiffness::ToolCompliance;

std::vector<Pose> stiffness_map_grid(const Pose& centre, double half_range_mm, double step_mm,
                                     dynamics::GridPlane plane = dynamics::GridPlane::xy) {
  dynamics::PlaneGrid grid;
  grid.centre = centre;
  grid.plane = plane;
  grid.half_range_mm = half_range_mm;
  grid.step_mm = step_mm;
  return *dynamics::plane_grid_poses(grid, 1e6);
}

/// Random strut stiffness 50…400 N/µm.
StiffnessParameters stiffness_map_springs(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  StiffnessParameters p;
  p.strut_count = 6;
  p.line = 1;
  for (int j = 0; j < 6; ++j) p.struts[j].stiffness_N_mm = 5e4 + 3.5e5 * unit(rng);
  return p;
}

/// The base-frame image of a pose under a turn about z (the machine's symmetry: frequency_map_test.cpp).
Pose stiffness_map_turned_about_z(const Pose& pose, double angle_deg) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(rad_from_deg(angle_deg), Eigen::Vector3d::UnitZ()).matrix();
  Pose turned;
  turned.position_mm = turn * pose.position_mm;
  turned.rotation = turn * pose.rotation * turn.transpose();
  return turned;
}

/// The translational block's spectrum at a pose, most compliant first (for the degeneracy of a direction).
Eigen::Vector3d stiffness_map_compliances(const ToolCompliance& c) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> s(c.compliance.topLeftCorner<3, 3>());
  return s.eigenvalues().reverse();
}

TEST(StiffnessMap, EachCellIsTheSinglePoseComputation) {
  std::mt19937_64 rng(1511);
  std::vector<std::pair<std::string, Machine>> machines;
  machines.emplace_back("ch5", test::machine_from_example("examples/machines/hexapod_ch5.yaml"));
  for (int i = 0; i < 3; ++i)
    machines.emplace_back(fmt::format("random {}", i), test::random_hexapod_machine(rng, i));
  for (const auto& [label, machine] : machines) {
    SCOPED_TRACE(label);
    const StiffnessParameters springs = stiffness_map_springs(rng);
    // Wide enough on the ch5 hexapod to leave its drives' range above and below.
    const auto poses = stiffness_map_grid(*machine.mechanism->complete_pose(machine.mechanism->home()), 300,
                                          100, dynamics::GridPlane::xz);
    auto map = stiffness::stiffness_map(poses, stiffness::strut_compliance_at(machine, springs));
    ASSERT_TRUE(map.ok()) << map.error().message;
    ASSERT_EQ(map->size(), poses.size());
    int with_value = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const auto& cell = (*map)[i];
      auto actuators = machine.mechanism->inverse(poses[i]);
      const bool in_range = actuators && check_actuator_range(machine, *actuators).ok();
      if (!in_range) {
        EXPECT_EQ(cell.status, actuators ? MapPointStatus::out_of_range : MapPointStatus::unreachable) << i;
        EXPECT_TRUE(std::isnan(cell.lowest_stiffness_N_um));
        continue;
      }
      auto single = stiffness::strut_compliance(*machine.mechanism, springs, poses[i]);
      if (!single) {
        EXPECT_EQ(cell.status, MapPointStatus::singular) << i;
        continue;
      }
      ASSERT_EQ(cell.status, MapPointStatus::ok) << i;
      ++with_value;
      // 1/λ_max of the translational block, in N/µm, and its eigenvector.
      const Eigen::Vector3d lambda = stiffness_map_compliances(*single);
      EXPECT_NEAR(cell.lowest_stiffness_N_um, 1e-3 / lambda[0], 1e-12 / lambda[0]) << i;
      EXPECT_NEAR(cell.direction.norm(), 1.0, 1e-12);
      const Eigen::Vector3d image = single->compliance.topLeftCorner<3, 3>() * cell.direction;
      EXPECT_LE((image - lambda[0] * cell.direction).norm(), 1e-9 * lambda[0]) << i;
      // Reproducible sign: the largest component positive.
      Eigen::Index largest = 0;
      cell.direction.cwiseAbs().maxCoeff(&largest);
      EXPECT_GT(cell.direction[largest], 0.0);
    }
    EXPECT_GT(with_value, 0);
    if (label == "ch5") {
      EXPECT_LT(with_value, static_cast<int>(poses.size()));
    }
  }
}

TEST(StiffnessMap, TheSymmetricCh5HexapodHasASymmetricMap) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto springs = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(springs.ok());
  const auto model = stiffness::strut_compliance_at(machine, *springs);
  for (const Pose& centre : {test::abc_pose(0, 0, 700, 0, 0, 0), test::abc_pose(0, 0, 650, 0, 0, 0)}) {
    const auto poses = stiffness_map_grid(centre, 150, 25);
    const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(poses.size()))));
    auto map = stiffness::stiffness_map(poses, model);
    ASSERT_TRUE(map.ok());
    // Mirror x → −x: cell (i, j) and cell (n − 1 − i, j), directions mirrored.
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const auto& a = (*map)[i + n * j];
        const auto& b = (*map)[(n - 1 - i) + n * j];
        ASSERT_EQ(a.status, b.status) << i << " " << j;
        if (a.status != MapPointStatus::ok) continue;
        EXPECT_NEAR(a.lowest_stiffness_N_um, b.lowest_stiffness_N_um, 1e-9 * a.lowest_stiffness_N_um);
        // A direction means something only where the weakest stiffness is single.
        const Eigen::Vector3d lambda = stiffness_map_compliances(*model(poses[i + n * j]));
        if (lambda[0] - lambda[1] < 1e-6 * lambda[0]) continue;
        const Eigen::Vector3d mirrored(-b.direction.x(), b.direction.y(), b.direction.z());
        EXPECT_NEAR(std::abs(a.direction.dot(mirrored)), 1.0, 1e-9) << i << " " << j;
      }
    }
    // Turned by 120° about z: the same values, the directions turned.
    std::vector<Pose> turned;
    for (const Pose& p : poses) turned.push_back(stiffness_map_turned_about_z(p, 120));
    auto turned_map = stiffness::stiffness_map(turned, model);
    ASSERT_TRUE(turned_map.ok());
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(rad_from_deg(120), Eigen::Vector3d::UnitZ()).matrix();
    int compared = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      const auto& a = (*map)[k];
      const auto& b = (*turned_map)[k];
      // The drives' range is symmetric too, so a point and its image are reachable alike.
      ASSERT_EQ(a.status, b.status) << k;
      if (a.status != MapPointStatus::ok) continue;
      ++compared;
      EXPECT_NEAR(a.lowest_stiffness_N_um, b.lowest_stiffness_N_um, 1e-9 * a.lowest_stiffness_N_um) << k;
      const Eigen::Vector3d lambda = stiffness_map_compliances(*model(poses[k]));
      if (lambda[0] - lambda[1] < 1e-6 * lambda[0]) continue;
      EXPECT_NEAR(std::abs((turn * a.direction).dot(b.direction)), 1.0, 1e-9) << k;
    }
    EXPECT_GT(compared, 0);
  }
}

TEST(StiffnessMap, AnyComplianceModelPlugsInAndItsErrorsSayWhy) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto springs = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(springs.ok());
  const auto struts = stiffness::strut_compliance_at(machine, *springs);
  const auto poses = stiffness_map_grid(machine.mechanism->home(), 40, 20);
  auto map = stiffness::stiffness_map(poses, struts);
  ASSERT_TRUE(map.ok());
  // A model twice as compliant: every value halves, the directions stay.
  auto softer = stiffness::stiffness_map(poses, [&](const Pose& p) -> Result<ToolCompliance> {
    auto c = struts(p);
    if (c) c->compliance *= 2.0;
    return c;
  });
  ASSERT_TRUE(softer.ok());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ASSERT_EQ((*map)[k].status, MapPointStatus::ok);
    EXPECT_NEAR((*softer)[k].lowest_stiffness_N_um, 0.5 * (*map)[k].lowest_stiffness_N_um,
                1e-12 * (*map)[k].lowest_stiffness_N_um);
  }
  // Errors about a pose become statuses; others stop the map.
  const std::vector<std::pair<ErrorCode, MapPointStatus>> codes = {
      {ErrorCode::unreachable, MapPointStatus::unreachable},
      {ErrorCode::limit_exceeded, MapPointStatus::out_of_range},
      {ErrorCode::singular, MapPointStatus::singular},
      {ErrorCode::not_converged, MapPointStatus::singular}};
  for (const auto& [code, status] : codes) {
    auto cells = stiffness::stiffness_map(
        poses, [code = code](const Pose&) -> Result<ToolCompliance> { return make_error(code, "no"); });
    ASSERT_TRUE(cells.ok());
    for (const auto& cell : *cells) {
      EXPECT_EQ(cell.status, status);
      EXPECT_TRUE(std::isnan(cell.lowest_stiffness_N_um));
      EXPECT_TRUE(cell.direction.array().isNaN().all());
    }
  }
  auto broken = stiffness::stiffness_map(poses, [](const Pose&) -> Result<ToolCompliance> {
    return make_error(ErrorCode::unsupported, "not this model");
  });
  ASSERT_FALSE(broken.ok());
  EXPECT_EQ(broken.error().message, "not this model");
  const auto s = stiffness::summarise_stiffness_map(*map);
  EXPECT_EQ(s.points, static_cast<int>(poses.size()));
  EXPECT_EQ(s.with_value, s.points);
  for (const auto& cell : *map) {
    EXPECT_GE(cell.lowest_stiffness_N_um, (*map)[s.lowest_index].lowest_stiffness_N_um);
    EXPECT_LE(cell.lowest_stiffness_N_um, (*map)[s.highest_index].lowest_stiffness_N_um);
  }
}

TEST(StiffnessMap, TheCsvHasAPoseAndAValueOrAReasonPerRow) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto springs = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(springs.ok());
  const auto poses = stiffness_map_grid(machine.mechanism->home(), 400, 400);  // corners beyond the range
  auto map = stiffness::stiffness_map(poses, stiffness::strut_compliance_at(machine, *springs));
  ASSERT_TRUE(map.ok());
  std::istringstream csv(formats::stiffness_map_csv(*machine.mechanism, poses, *map));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(
      line,
      "x_mm,y_mm,z_mm,psi_deg,theta_deg,gamma_deg,lowest_stiffness_N_um,direction_x,direction_y,direction_z,"
      "status")
      << line;
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    const auto& cell = (*map)[rows++];
    const std::string status = line.substr(line.rfind(',') + 1);
    EXPECT_EQ(status, dynamics::to_string(cell.status));
    if (cell.status != MapPointStatus::ok) {
      EXPECT_NE(line.find(",,,,"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(rows, poses.size());
  // The centre row: home, with the value.
  EXPECT_EQ((*map)[4].status, MapPointStatus::ok);
}

}  // namespace
}  // namespace pkm
