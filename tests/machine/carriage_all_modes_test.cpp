// Every assembly mode of the carriage machines (machine/carriage_assembly_modes.hpp): on the shipped
// hexaglide, rotopod and triglide and on random variants of their geometry (every joint, guide point and
// strut length moved at random), at random poses near home, the true pose is among the modes and is the one
// labelled 0, every mode fits the struts to 1e-8 mm, no two modes are the same pose, and the labels are
// unique.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <set>

#include "machine/solution_set.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

// `mechanism` with every geometry value moved by up to `spread` (mm, or rad for angles) at random.
std::unique_ptr<Mechanism> shaken(const Mechanism& mechanism, std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<GeometryGroup> groups = mechanism.geometry_parameters();
  for (GeometryGroup& group : groups)
    for (double& value : group.values) value += spread * (group.unit == "rad" ? 0.002 : 1.0) * u(rng);
  auto changed = mechanism.with_geometry(groups);
  EXPECT_TRUE(changed) << changed.error().message;
  return std::move(*changed);
}

void expect_every_mode(const Mechanism& mechanism, std::mt19937_64& rng, const std::string& what) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Pose pose = mechanism.home();
    pose.position_mm += Eigen::Vector3d(20 * u(rng), 20 * u(rng), 10 * u(rng));
    pose.rotation = Eigen::AngleAxisd(0.05 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()) *
                    pose.rotation;
    auto complete = mechanism.complete_pose(pose);
    ASSERT_TRUE(complete);
    pose = *complete;
    auto q = mechanism.inverse(pose);
    if (!q) continue;
    SCOPED_TRACE(what + ", trial " + std::to_string(trial));
    auto modes = mechanism.assembly_modes(*q);
    ASSERT_TRUE(modes) << modes.error().message;
    ASSERT_FALSE(modes->solutions.empty());
    EXPECT_EQ(modes->report.real, static_cast<int>(modes->solutions.size()));
    bool found = false;
    std::set<int> labels;
    for (std::size_t i = 0; i < modes->solutions.size(); ++i) {
      const FkSolution& s = modes->solutions[i];
      EXPECT_LE(s.residual_mm, 1e-8) << "mode " << i;
      EXPECT_TRUE(labels.insert(s.branch).second) << "label " << s.branch << " twice";
      const bool same = (s.pose.position_mm - pose.position_mm).norm() < 1e-6 &&
                        (s.pose.rotation - pose.rotation).cwiseAbs().maxCoeff() < 1e-8;
      if (same) {
        found = true;
        EXPECT_EQ(s.branch, 0) << "the true pose is the machine's own mode";
      }
      for (std::size_t k = 0; k < i; ++k)
        EXPECT_GT((s.pose.position_mm - modes->solutions[k].pose.position_mm).norm() +
                      (s.pose.rotation - modes->solutions[k].pose.rotation).norm(),
                  1e-6)
            << "modes " << k << " and " << i << " are one pose";
    }
    EXPECT_TRUE(found) << "the true pose is missing";
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

TEST(CarriageAllModes, TheTruePoseIsAmongTheModesOfEveryCarriageMachine) {
  std::mt19937_64 rng(42);
  for (const char* file : {"hexaglide.yaml", "rotopod.yaml", "triglide.yaml"}) {
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    expect_every_mode(*machine.mechanism, rng, file);
    for (int variant = 0; variant < 3; ++variant) {
      const auto random = shaken(*machine.mechanism, rng, 5.0);
      expect_every_mode(*random, rng, std::string(file) + " variant " + std::to_string(variant));
    }
  }
}

// The symmetric rotopod loses solutions to infinity; the report says how many, and the real, complex and
// lost ones are the hexapod's 40.
TEST(CarriageAllModes, TheReportAccountsForAllFortySolutions) {
  for (const char* file : {"hexaglide.yaml", "rotopod.yaml"}) {
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    auto q = machine.mechanism->inverse(machine.mechanism->home());
    ASSERT_TRUE(q);
    auto modes = machine.mechanism->assembly_modes(*q);
    ASSERT_TRUE(modes) << modes.error().message;
    const AssemblyModeReport& r = modes->report;
    EXPECT_EQ(r.real + r.complex + r.at_infinity + r.singular, 40) << file << ": " << r.method;
    EXPECT_EQ(modes->solutions.front().branch, 0) << file;
  }
}

}  // namespace
}  // namespace pkm
