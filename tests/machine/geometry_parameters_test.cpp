// The calibratable geometry of every mechanism: Mechanism::geometry_parameters() and
// with_geometry() for every shipped machine (a clone keeps the inverse kinematics, each value moves it, the
// groups are in the frames their keys say, wrong shapes fail), and the drive-offset decorator
// (machine/actuator_offsets.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "machine/actuator_offsets.hpp"
#include "machine/hexapod.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

std::vector<std::string> geomparam_example_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("examples/machines"))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

Machine geomparam_load(const std::string& path) {
  auto machine = load_machine_file(path);
  if (!machine) throw std::runtime_error(machine.error().message);
  return std::move(machine.value());
}

// Reachable poses near home: the controlled coordinates moved by up to ±8 mm and ±1.5°, completed.
std::vector<Pose> geomparam_poses(const Mechanism& mech, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<Pose> poses{mech.home()};
  const AxisMask mask = mech.controlled_axes();
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(poses.size()) < count; ++attempt) {
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis])
        c[axis] += axis < 3 ? test::uniform(rng, -8, 8) : rad_from_deg(test::uniform(rng, -1.5, 1.5));
    }
    auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
    if (pose && mech.inverse(*pose)) poses.push_back(*pose);
  }
  return poses;
}

// Largest |IK_a − IK_b| over the poses; +∞ when one of them cannot reach a pose the other can.
double geomparam_ik_difference(const Mechanism& a, const Mechanism& b, const std::vector<Pose>& poses) {
  double worst = 0.0;
  for (const Pose& pose : poses) {
    auto qa = a.inverse(pose);
    auto qb = b.inverse(pose);
    if (!qa || !qb) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, (*qa - *qb).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(GeometryParameters, EveryShippedMachineHasGroupsOfConsistentShape) {
  const auto files = geomparam_example_files();
  ASSERT_GE(files.size(), 13u);
  for (const auto& file : files) {
    const Machine m = geomparam_load(file);
    const auto groups = m.mechanism->geometry_parameters();
    ASSERT_FALSE(groups.empty()) << file;
    for (const auto& g : groups) {
      EXPECT_FALSE(g.key.empty()) << file;
      EXPECT_GT(g.rows, 0) << file << " " << g.key;
      EXPECT_EQ(g.values.size(), static_cast<std::size_t>(g.rows * g.columns())) << file << " " << g.key;
      EXPECT_EQ(
          std::count_if(groups.begin(), groups.end(), [&](const GeometryGroup& o) { return o.key == g.key; }),
          1)
          << file << " " << g.key;
    }
  }
}

TEST(GeometryParameters, CloneOfEveryShippedMachineHasTheSameKinematics) {
  for (const auto& file : geomparam_example_files()) {
    const Machine m = geomparam_load(file);
    const Mechanism& mech = *m.mechanism;
    auto clone = mech.with_geometry(mech.geometry_parameters());
    ASSERT_TRUE(clone.ok()) << file << ": " << clone.error().message;
    const Mechanism& copy = **clone;
    EXPECT_EQ(copy.type(), mech.type()) << file;
    EXPECT_EQ(copy.convention(), mech.convention()) << file;
    EXPECT_LT((copy.home().position_mm - mech.home().position_mm).norm(), 1e-12) << file;
    EXPECT_LT((copy.home().rotation - mech.home().rotation).norm(), 1e-12) << file;
    const auto poses = geomparam_poses(mech, 12, 11);
    ASSERT_GE(poses.size(), 8u) << file;
    EXPECT_LT(geomparam_ik_difference(mech, copy, poses), 1e-12) << file;
    // The same assembly mode: FK from home lands on branch 0 in both.
    const auto q = mech.inverse(poses[1]);
    auto fa = mech.forward(*q, mech.home());
    auto fb = copy.forward(*q, copy.home());
    ASSERT_TRUE(fa.ok() && fb.ok()) << file;
    EXPECT_EQ(fa->branch, fb->branch) << file;
    EXPECT_LT((fa->pose.position_mm - fb->pose.position_mm).norm(), 1e-8) << file;
    // And the groups come back as they went in.
    const auto again = copy.geometry_parameters();
    const auto original = mech.geometry_parameters();
    ASSERT_EQ(again.size(), original.size());
    for (std::size_t g = 0; g < again.size(); ++g) EXPECT_EQ(again[g].values, original[g].values) << file;
  }
}

TEST(GeometryParameters, EveryValueOfEveryShippedMachineMovesItsInverseKinematics) {
  for (const auto& file : geomparam_example_files()) {
    const Machine m = geomparam_load(file);
    const Mechanism& mech = *m.mechanism;
    const auto poses = geomparam_poses(mech, 4, 5);
    const auto groups = mech.geometry_parameters();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (std::size_t i = 0; i < groups[g].values.size(); ++i) {
        auto perturbed = groups;
        // 0.5 mm: a move across a strut changes its length by about 0.5²/(2 L) only, still ≫ rounding.
        perturbed[g].values[i] += 0.5;
        auto moved = mech.with_geometry(perturbed);
        ASSERT_TRUE(moved.ok()) << file << " " << groups[g].key << "[" << i << "]: " << moved.error().message;
        EXPECT_GT(geomparam_ik_difference(mech, **moved, poses), 1e-7)
            << file << " " << groups[g].key << "[" << i << "]";
        EXPECT_EQ((*moved)->geometry_parameters()[g].values[i], perturbed[g].values[i]) << file;
      }
    }
  }
}

// The keys say the frame: base_joints are the base-side strut ends, platform_joints_from_tool the
// platform-side ones in the tool frame (p + R·b).
TEST(GeometryParameters, JointGroupsAreInTheFramesTheirKeysName) {
  int checked = 0;
  for (const auto& file : geomparam_example_files()) {
    const Machine m = geomparam_load(file);
    const Mechanism& mech = *m.mechanism;
    const Pose pose = geomparam_poses(mech, 2, 3).back();
    StrutJointPoints ends;
    const int n = mech.strut_ends(pose, ends);
    ASSERT_EQ(n, mech.actuator_count()) << file;
    for (const auto& g : mech.geometry_parameters()) {
      const bool base = g.key == "base_joints";
      if (!base && g.key != "platform_joints_from_tool") continue;
      ASSERT_EQ(g.rows, n) << file;
      for (int j = 0; j < n; ++j) {
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        for (int c = 0; c < g.columns(); ++c) p[c] = g.values[static_cast<std::size_t>(j * g.columns() + c)];
        const Eigen::Vector3d want = base ? p : pose.to_base(p);
        const Eigen::Vector3d& got = base ? ends.base_mm[j] : ends.platform_mm[j];
        EXPECT_LT((want - got).norm(), 1e-9) << file << " " << g.key << " " << j;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(GeometryParameters, WrongShapesAndValuesFail) {
  for (const auto& file : geomparam_example_files()) {
    const Machine m = geomparam_load(file);
    const Mechanism& mech = *m.mechanism;
    const auto groups = mech.geometry_parameters();

    auto missing = groups;
    missing.pop_back();
    EXPECT_FALSE(mech.with_geometry(missing).ok()) << file;
    auto extra = groups;
    extra.push_back(groups.front());
    EXPECT_FALSE(mech.with_geometry(extra).ok()) << file;
    auto renamed = groups;
    renamed.front().key += "_x";
    EXPECT_FALSE(mech.with_geometry(renamed).ok()) << file;
    auto short_row = groups;
    short_row.front().values.pop_back();
    EXPECT_FALSE(mech.with_geometry(short_row).ok()) << file;
    auto fewer_rows = groups;
    fewer_rows.front().rows -= 1;
    fewer_rows.front().values.resize(
        static_cast<std::size_t>(fewer_rows.front().rows * fewer_rows.front().columns()));
    EXPECT_FALSE(mech.with_geometry(fewer_rows).ok()) << file;
    auto not_finite = groups;
    not_finite.back().values.back() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(mech.with_geometry(not_finite).ok()) << file;
  }
}

// ---- the drive-offset decorator ----

ActuatorVector geomparam_offsets(int n, double scale) {
  ActuatorVector d(n);
  for (int j = 0; j < n; ++j) d[j] = scale * (0.3 - 0.17 * j);
  return d;
}

TEST(ActuatorOffsets, InverseIsInnerLessTheOffsetsAndForwardUndoesIt) {
  for (const auto& file : geomparam_example_files()) {
    const Machine m = geomparam_load(file);
    const Mechanism& inner = *m.mechanism;
    const int n = inner.actuator_count();
    const ActuatorVector d = geomparam_offsets(n, inner.actuators_are_angles() ? 1e-3 : 1.0);
    auto clone = inner.with_geometry(inner.geometry_parameters());
    ASSERT_TRUE(clone.ok()) << file;
    const auto decorated = with_actuator_offsets(std::move(clone.value()), d);
    EXPECT_EQ(decorated->type(), inner.type());
    EXPECT_EQ(decorated->actuator_count(), n);
    EXPECT_EQ(decorated->actuators_are_angles(), inner.actuators_are_angles());
    EXPECT_EQ(decorated->is_planar(), inner.is_planar());
    EXPECT_LT((decorated->home().position_mm - inner.home().position_mm).norm(), 1e-15);
    for (const Pose& pose : geomparam_poses(inner, 8, 17)) {
      const auto q = inner.inverse(pose);
      const auto r = decorated->inverse(pose);
      ASSERT_TRUE(q.ok() && r.ok()) << file;
      EXPECT_LT((*r - (*q - d)).cwiseAbs().maxCoeff(), 1e-12) << file;
      std::array<double, kMaxActuators> hot{};
      ASSERT_TRUE(decorated->actuator_values(pose, hot.data())) << file;
      for (int j = 0; j < n; ++j) EXPECT_NEAR(hot[j], (*r)[j], 1e-12) << file;
      // FK of the readings is the pose again, with the inner solver's residual.
      auto fk = decorated->forward(*r, decorated->home());
      ASSERT_TRUE(fk.ok()) << file << ": " << fk.error().message;
      EXPECT_LT((fk->pose.position_mm - pose.position_mm).norm(), 1e-7) << file;
      EXPECT_LT((fk->pose.rotation - pose.rotation).norm(), 1e-9) << file;
      EXPECT_EQ(fk->branch, 0) << file;
      // Readings taken as true lengths would be another pose: the offsets matter.
      auto wrong = inner.forward(*r, inner.home());
      if (wrong) {
        EXPECT_GT((wrong->pose.position_mm - pose.position_mm).norm(), 1e-3) << file;
      }
      // Jacobians are the inner ones.
      auto ja = inner.jacobian(pose);
      auto jb = decorated->jacobian(pose);
      ASSERT_TRUE(ja.ok() && jb.ok());
      EXPECT_EQ(*ja, *jb) << file;
    }
  }
}

TEST(ActuatorOffsets, WarmForwardUsesTheInnerWorkspace) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto decorated = with_actuator_offset_parameters(*m.mechanism);
  ASSERT_TRUE(decorated.ok());
  auto groups = (*decorated)->geometry_parameters();
  groups.back().values = {0.2, -0.1, 0.05, 0.3, -0.25, 0.0};
  auto offset = (*decorated)->with_geometry(groups);
  ASSERT_TRUE(offset.ok()) << offset.error().message;
  const Mechanism& mech = **offset;
  const auto& wrapper = dynamic_cast<const ActuatorOffsets&>(mech);

  auto workspace = mech.make_fk_workspace();
  // The inner hexapod made it, so its owner check accepts it and its state carries from call to call.
  EXPECT_EQ(workspace->owner(), &wrapper.inner());
  auto* hexapod_workspace = dynamic_cast<HexapodFkWorkspace*>(workspace.get());
  ASSERT_NE(hexapod_workspace, nullptr);
  Pose previous = mech.home();
  for (int i = 1; i <= 10; ++i) {
    Pose target = mech.home();
    target.position_mm.x() += 0.2 * i;
    const auto readings = mech.inverse(target);
    ASSERT_TRUE(readings.ok());
    auto fk = mech.forward_warm(*readings, previous, FkOptions{}, *workspace);
    ASSERT_TRUE(fk.ok()) << fk.error().message;
    EXPECT_LT((fk->pose.position_mm - target.position_mm).norm(), 1e-8) << i;
    previous = fk->pose;
  }
  EXPECT_GE(hexapod_workspace->platform.solutions_kept, 4);
}

TEST(ActuatorOffsets, GroupsEndWithTheOffsetsAndSplitBack) {
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  const Mechanism& inner = *m.mechanism;
  auto wrapped = with_actuator_offset_parameters(inner);
  ASSERT_TRUE(wrapped.ok());
  const auto groups = (*wrapped)->geometry_parameters();
  const auto inner_groups = inner.geometry_parameters();
  ASSERT_EQ(groups.size(), inner_groups.size() + 1);
  const GeometryGroup& offsets = groups.back();
  EXPECT_EQ(offsets.key, "actuator_offsets");
  EXPECT_EQ(offsets.row_symbol, "dL");
  EXPECT_EQ(offsets.unit, "rad");  // rotopod carriages are angles
  EXPECT_EQ(offsets.rows, 6);
  EXPECT_EQ(offsets.columns(), 1);
  EXPECT_EQ(offsets.values, std::vector<double>(6, 0.0));

  // A clone of a wrapped mechanism keeps its offsets, and is not wrapped twice.
  auto changed = groups;
  changed.back().values = {1e-3, 0, 0, 0, 0, -2e-3};
  changed.front().values[0] += 0.25;  // the circle's centre x
  auto rebuilt = (*wrapped)->with_geometry(changed);
  ASSERT_TRUE(rebuilt.ok()) << rebuilt.error().message;
  auto again = with_actuator_offset_parameters(**rebuilt);
  ASSERT_TRUE(again.ok());
  const auto again_groups = (*again)->geometry_parameters();
  ASSERT_EQ(again_groups.size(), groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) EXPECT_EQ(again_groups[g].values, changed[g].values);
  const auto& decorator = dynamic_cast<const ActuatorOffsets&>(**again);
  EXPECT_EQ(decorator.inner().geometry_parameters().front().values, changed.front().values);

  // The carriages move as the inner ones do at the geometric angle, reading + offset.
  Eigen::Vector3d first_a, second_a, first_b, second_b;
  (*again)->base_joint_motion(5, 0.4, first_a, second_a);
  decorator.inner().base_joint_motion(5, 0.4 - 2e-3, first_b, second_b);
  EXPECT_LT((first_a - first_b).norm(), 1e-15);
  EXPECT_LT((second_a - second_b).norm(), 1e-15);

  // The offsets group has its shape checked like any other.
  auto short_offsets = changed;
  short_offsets.back().values.pop_back();
  EXPECT_FALSE((*wrapped)->with_geometry(short_offsets).ok());
  EXPECT_FALSE((*wrapped)->with_geometry(inner_groups).ok());
}

TEST(ActuatorOffsets, EnumeratedAssemblyModesIncludeThePoseOfTheReadings) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch3.yaml");
  const ActuatorVector d = geomparam_offsets(6, 0.5);
  auto clone = m.mechanism->with_geometry(m.mechanism->geometry_parameters());
  ASSERT_TRUE(clone.ok());
  const auto decorated = with_actuator_offsets(std::move(clone.value()), d);
  Pose target = decorated->home();
  target.position_mm += Eigen::Vector3d(3, -2, 4);
  const auto readings = decorated->inverse(target);
  ASSERT_TRUE(readings.ok());
  auto all = decorated->forward_all(*readings);
  ASSERT_TRUE(all.ok()) << all.error().message;
  double nearest = 1e300;
  for (const auto& s : *all) nearest = std::min(nearest, (s.pose.position_mm - target.position_mm).norm());
  EXPECT_LT(nearest, 1e-7);
  // Readings of the wrong count are refused, not read past their end.
  EXPECT_FALSE(decorated->forward(readings->head(5), decorated->home()).ok());
}

}  // namespace
}  // namespace pkm
