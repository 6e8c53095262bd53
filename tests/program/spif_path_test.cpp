// The forming paths of `pkm spif program`: read back as LinuxCNC's dialect, on generated options, they are
// the circles asked for (radius, plane, sense), in order, and the seeds' default is the seeds' cone.
#include "program/spif_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "planning/plan_test_support.hpp"
#include "test_support.hpp"

namespace pkm::test {
namespace {

using program::MoveKind;

program::CanonicalProgram read_back(const program::SpifPathOptions& options) {
  const Machine machine = machine_from_example("examples/machines/hexapod_ch3.yaml");
  auto text = program::spif_program_text(options);
  EXPECT_TRUE(text) << text.error().message;
  return gcode_for(machine, text ? *text : std::string(), "spif.ngc");
}

TEST(SpifPath, GeneratedPathsAreTheCirclesAsked) {
  std::mt19937 random(3081);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    program::SpifPathOptions o;
    o.planes = 1 + static_cast<int>(30 * unit(random));
    o.radius_mm = 10.0 + 90.0 * unit(random);
    o.radius_step_mm = unit(random) * 0.9 * o.radius_mm / o.planes;
    o.step_down_mm = 0.2 + 1.8 * unit(random);
    o.counter_clockwise = unit(random) < 0.5;
    o.depth_up = unit(random) < 0.5;
    o.kind = unit(random) < 0.5 ? program::SpifPathKind::helix : program::SpifPathKind::planes;
    o.z1_mm = -50.0 + 100.0 * unit(random);
    o.centre_mm = Eigen::Vector2d(-20.0 + 40.0 * unit(random), -20.0 + 40.0 * unit(random));
    const auto program = read_back(o);
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    const double depth = o.depth_up ? o.step_down_mm : -o.step_down_mm;
    const Eigen::Vector3d centre(o.centre_mm.x(), o.centre_mm.y(), 0.0);
    int n = 0;
    Eigen::Vector3d at = program.moves.front().end_mm;
    EXPECT_NEAR((at - centre).head<2>().norm(), o.radius_mm, 1e-4);
    for (const auto& move : program.moves) {
      if (move.kind == MoveKind::arc) {
        const double r = o.radius_mm - n * o.radius_step_mm;
        EXPECT_NEAR((move.end_mm - centre).head<2>().norm(), r, 1e-4) << "circle " << n;
        // X and I are written to 1e-4 mm each.
        EXPECT_NEAR((move.center_mm - centre).head<2>().norm(), 0.0, 2e-4) << "circle " << n;
        EXPECT_NEAR(move.normal.z(), o.counter_clockwise ? 1.0 : -1.0, 1e-12);
        // A whole turn: it ends where it began, on its plane or one step further along the helix.
        EXPECT_LT((move.end_mm - at).head<2>().norm(), 1e-4);
        const double z_end = o.z1_mm + (o.kind == program::SpifPathKind::helix ? n + 1 : n) * depth;
        EXPECT_NEAR(move.end_mm.z(), z_end, 1e-4) << "circle " << n;
        EXPECT_NEAR(move.feed_mm_min, o.feed_mm_min, 1e-9);
        ++n;
      }
      at = move.end_mm;
    }
    EXPECT_EQ(n, o.planes);
  }
}

// The seeds' SPIF path (Smirnov 2019, §3.8.1): 21 circles from R 75 mm, each 0.5 mm smaller, 1.06 mm apart:
// 2π·1470 mm of circles, 21.2 mm deep.
TEST(SpifPath, TheDefaultIsTheSeedsCone) {
  const auto program = read_back({});
  double circles_mm = 0.0;
  double lowest_z = 0.0;
  int arcs = 0;
  for (const auto& move : program.moves) {
    if (move.kind != MoveKind::arc) continue;
    ++arcs;
    circles_mm += 2.0 * std::numbers::pi * (move.end_mm - move.center_mm).head<2>().norm();
    lowest_z = std::min(lowest_z, move.end_mm.z());
  }
  EXPECT_EQ(arcs, 21);
  EXPECT_NEAR(circles_mm, 2.0 * std::numbers::pi * 1470.0, 1e-3);
  EXPECT_NEAR(lowest_z, -21.2, 1e-9);
}

TEST(SpifPath, ImpossibleOptionsAreNamed) {
  auto refused = [](program::SpifPathOptions o, const std::string& word) {
    auto text = program::spif_program_text(o);
    ASSERT_FALSE(text);
    EXPECT_NE(text.error().message.find(word), std::string::npos) << text.error().message;
  };
  program::SpifPathOptions o;
  o.radius_step_mm = 4.0;  // the 21st circle would have R −5 mm
  refused(o, "radius step");
  o = {};
  o.planes = 0;
  refused(o, "planes");
  o = {};
  o.step_down_mm = -1.0;
  refused(o, "step down");
  o = {};
  o.feed_mm_min = 0.0;
  refused(o, "feed");
  o = {};
  o.z1_mm = std::nan("");
  refused(o, "z1");
}

// A wall given as a profile: the planes every step down to its deepest row, each circle's radius the wall's
// there (linear between rows); two rows make the cone, the same circles as the cone's own options.
TEST(SpifPath, AProfileGivesTheWallsRadiusAtEveryPlane) {
  program::SpifPathOptions o;
  o.step_down_mm = 1.0;
  o.profile = {{0.0, 75.0}, {10.0, 70.0}, {20.0, 60.0}};
  const auto program = read_back(o);
  std::vector<double> radii;
  for (const auto& move : program.moves)
    if (move.kind == MoveKind::arc) radii.push_back((move.end_mm - move.center_mm).head<2>().norm());
  ASSERT_EQ(radii.size(), 21u);
  for (std::size_t n = 0; n < radii.size(); ++n) {
    const double depth = static_cast<double>(n);
    const double wall = depth <= 10.0 ? 75.0 - 0.5 * depth : 70.0 - (depth - 10.0);
    EXPECT_NEAR(radii[n], wall, 1e-4) << "plane " << n;
  }
  program::SpifPathOptions cone;
  cone.profile = {{0.0, 75.0}, {21.2, 65.0}};
  const auto from_profile = read_back(cone);
  const auto seeds = read_back({});
  ASSERT_EQ(from_profile.moves.size(), seeds.moves.size());
  for (std::size_t m = 0; m < seeds.moves.size(); ++m)
    EXPECT_LT((from_profile.moves[m].end_mm - seeds.moves[m].end_mm).norm(), 1e-9) << m;
}

}  // namespace
}  // namespace pkm::test
