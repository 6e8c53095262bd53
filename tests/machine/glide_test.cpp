// Glide machines (Smirnov 2019, §2.2.8; Rusanov et al.): the sphere–line IK and its branches, IK∘FK round
// trips for hexaglides (6 guides) and triglides (3 guides), the Jacobian, unreachable and singular poses, and
// the file.
#include "machine/glide.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <random>
#include <string>

#include "core/units.hpp"
#include "source_paths.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Pose glide_random_pose(std::mt19937_64& rng, const Pose& around, double mm, double deg) {
  PoseVector c = vector_from_pose(AngleConvention::abc, around);
  for (int k = 0; k < 3; ++k) c[k] += test::uniform(rng, -mm, mm);
  for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(test::uniform(rng, -deg, deg));
  return pose_from_vector(AngleConvention::abc, c);
}

Eigen::Vector3d glide_random_vector(std::mt19937_64& rng, double size) {
  return {test::uniform(rng, -size, size), test::uniform(rng, -size, size), test::uniform(rng, -size, size)};
}

// A machine near an example layout: guide points, directions, lengths and joints jittered.
Glide jittered(const Glide& example, std::mt19937_64& rng) {
  GlideGeometry g = example.geometry();
  for (int j = 0; j < g.count; ++j) {
    g.guide_points_mm[j] += glide_random_vector(rng, 20);
    g.guide_directions[j] = (g.guide_directions[j] + glide_random_vector(rng, 0.05)).normalized();
    g.strut_lengths_mm[j] += test::uniform(rng, -15, 15);
    g.platform_joints_mm[j] += glide_random_vector(rng, 10);
  }
  return Glide(g, AngleConvention::abc, example.home());
}

const Glide& as_glide(const Machine& m) {
  return dynamic_cast<const Glide&>(*m.mechanism);
}

TEST(Glide, ExamplesLoadWithTheirDegreesOfFreedom) {
  const Machine hexaglide = test::machine_from_example("examples/machines/hexaglide.yaml");
  EXPECT_EQ(hexaglide.mechanism->actuator_count(), 6);
  EXPECT_EQ(hexaglide.mechanism->controlled_axes().count(), 6);
  const Machine triglide = test::machine_from_example("examples/machines/triglide.yaml");
  EXPECT_EQ(triglide.mechanism->actuator_count(), 3);
  EXPECT_EQ(triglide.mechanism->controlled_axes().count(), 3);
  EXPECT_FALSE(triglide.mechanism->controlled_axes().controlled[3]);
}

TEST(Glide, CarriagesSitOnTheirStrutSpheresAndBranchesOrderTheRoots) {
  const Machine m = test::machine_from_example("examples/machines/hexaglide.yaml");
  const Glide& glide = as_glide(m);
  GlideGeometry flipped = glide.geometry();
  for (int j = 0; j < 6; ++j) flipped.branches[j] = -flipped.branches[j];
  const Glide other(flipped, AngleConvention::abc, glide.home());
  std::mt19937_64 rng(1);
  for (int i = 0; i < 500; ++i) {
    const Pose pose = glide_random_pose(rng, glide.home(), 40, 4);
    const auto s = glide.inverse(pose);
    const auto t = other.inverse(pose);
    ASSERT_TRUE(s.ok() && t.ok());
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d b = pose.to_base(glide.geometry().platform_joints_mm[j]);
      EXPECT_NEAR((b - glide.carriage_mm(j, (*s)[j])).norm(), glide.geometry().strut_lengths_mm[j], 1e-9);
      EXPECT_NEAR((b - glide.carriage_mm(j, (*t)[j])).norm(), glide.geometry().strut_lengths_mm[j], 1e-9);
      // +1 is the root further along the guide direction.
      const double plus = glide.geometry().branches[j] > 0 ? (*s)[j] : (*t)[j];
      const double minus = glide.geometry().branches[j] > 0 ? (*t)[j] : (*s)[j];
      EXPECT_GT(plus, minus);
    }
  }
}

// Round trips over `geometries` jittered machines, each on >= 1000 accepted poses near home.
void round_trips(const char* example_file, std::uint64_t seed, double mm, double deg) {
  const Machine m = test::machine_from_example(example_file);
  std::mt19937_64 rng(seed);
  FkOptions options;
  options.tolerance_mm = 1e-12;
  for (int g = 0; g < 5; ++g) {
    const Glide glide = jittered(as_glide(m), rng);
    ASSERT_GT(glide.guide_conditioning(glide.home()), 0.1) << "generator produced a singular home";
    const double home_det = glide.strut_line_determinant(glide.home());
    int accepted = 0, skipped = 0;
    while (accepted < 1000) {
      const Pose truth = *glide.complete_pose(glide_random_pose(rng, glide.home(), mm, deg));
      // Near a singularity "the" pose is not defined: skip (and count) poses near one or across one from
      // home.
      const double det = glide.strut_line_determinant(truth);
      if (glide.guide_conditioning(truth) < 0.1 || det * home_det <= 0 ||
          std::abs(det) < 0.2 * std::abs(home_det)) {
        ++skipped;
        continue;
      }
      ++accepted;
      const auto s = glide.inverse(truth);
      ASSERT_TRUE(s.ok()) << s.error().message;
      const auto fk = glide.forward(*s, glide_random_pose(rng, truth, 1, 0.5), options);
      ASSERT_TRUE(fk.ok()) << fk.error().message;
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-9);
      EXPECT_LT(d.rotation_rad, 1e-11);
      const auto back = glide.inverse(fk->pose);
      ASSERT_TRUE(back.ok());
      EXPECT_LE((*back - *s).cwiseAbs().maxCoeff(), 1e-9);
    }
    EXPECT_LT(skipped, 200) << "too many near-singular samples: the generator is off";
  }
}

TEST(GlideProperty, HexaglideInverseThenForwardRoundTrips) {
  round_trips("examples/machines/hexaglide.yaml", 20260502, 40, 4);
}

TEST(GlideProperty, TriglideInverseThenForwardRoundTrips) {
  round_trips("examples/machines/triglide.yaml", 20260503, 60, 0);
}

TEST(Glide, TriglideKeepsItsOrientation) {
  const Machine m = test::machine_from_example("examples/machines/triglide.yaml");
  const auto s = m.mechanism->inverse(test::abc_pose(10, -20, 320, 0, 0, 0));
  ASSERT_TRUE(s.ok());
  // Angles in the pose are ignored (only x, y, z are controlled); FK returns the level platform.
  const auto tilted = m.mechanism->inverse(test::abc_pose(10, -20, 320, 5, 5, 5));
  ASSERT_TRUE(tilted.ok());
  EXPECT_LE((*s - *tilted).cwiseAbs().maxCoeff(), 1e-12);
  const auto fk = m.mechanism->forward(*s, test::abc_pose(0, 0, 300, 3, -2, 1));
  ASSERT_TRUE(fk.ok()) << fk.error().message;
  EXPECT_LT((fk->pose.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT((fk->pose.position_mm - Eigen::Vector3d(10, -20, 320)).norm(), 1e-8);
}

void expect_jacobian_matches_finite_differences(const Glide& glide, const Pose& pose) {
  const auto j = glide.jacobian(pose);
  ASSERT_TRUE(j.ok()) << j.error().message;
  const PoseVector c = vector_from_pose(AngleConvention::abc, pose);
  const int n = glide.controlled_axes().count();
  ASSERT_EQ(j->cols(), n);
  for (int k = 0; k < n; ++k) {
    const double h = k < 3 ? 1e-4 : 1e-6;
    PoseVector cp = c, cm = c;
    cp[k] += h;
    cm[k] -= h;
    const auto sp = glide.inverse(pose_from_vector(AngleConvention::abc, cp));
    const auto sm = glide.inverse(pose_from_vector(AngleConvention::abc, cm));
    ASSERT_TRUE(sp.ok() && sm.ok());
    const ActuatorVector fd = (*sp - *sm) / (2 * h);
    EXPECT_LT((fd - j->col(k)).cwiseAbs().maxCoeff(), 1e-5 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
        << "column " << k;
  }
}

TEST(Glide, JacobianMatchesFiniteDifferencesOfInverse) {
  std::mt19937_64 rng(7);
  for (const char* file : {"examples/machines/hexaglide.yaml", "examples/machines/triglide.yaml"}) {
    const Machine m = test::machine_from_example(file);
    for (int g = 0; g < 5; ++g) {
      const Glide glide = jittered(as_glide(m), rng);
      const Pose pose = *glide.complete_pose(glide_random_pose(rng, glide.home(), 30, 3));
      expect_jacobian_matches_finite_differences(glide, pose);
    }
  }
}

TEST(Glide, StrutsThatCannotReachTheirGuidesAreUnreachable) {
  const Machine m = test::machine_from_example("examples/machines/hexaglide.yaml");
  const auto s = m.mechanism->inverse(test::abc_pose(0, 0, -900, 0, 0, 0));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::unreachable);
  EXPECT_NE(s.error().message.find("carriage 1"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("mm too far"), std::string::npos) << s.error().message;
  const auto j = m.mechanism->jacobian(test::abc_pose(0, 0, -900, 0, 0, 0));
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error().code, ErrorCode::unreachable);
}

TEST(Glide, StrutPerpendicularToItsGuideIsSingular) {
  // Vertical guides (a linear delta). At the singular pose platform joint 1 is exactly one strut length from
  // guide 1, so the two roots merge (discriminant exactly 0): the carriage position exists but its speed does
  // not.
  GlideGeometry g;
  g.count = 3;
  for (int j = 0; j < 3; ++j) {
    const double a = rad_from_deg(90.0 + 120.0 * j);
    g.guide_points_mm[j] = {400 * std::cos(a), 400 * std::sin(a), 0};
    g.guide_directions[j] = Eigen::Vector3d::UnitZ();
    g.strut_lengths_mm[j] = 500;
    g.platform_joints_mm[j] = {50 * std::cos(a), 50 * std::sin(a), 0};
  }
  g.guide_points_mm[0] = {0, 400, 0};  // exact numbers for leg 1
  g.platform_joints_mm[0] = {0, 50, 0};
  const Glide glide(g, AngleConvention::abc, test::abc_pose(0, 0, -300, 0, 0, 0));
  EXPECT_GT(glide.guide_conditioning(glide.home()), 0.5);
  const Pose singular =
      test::abc_pose(0, -150, 7, 0, 0, 0);  // joint 1 at (0, -100, 7): 500 mm from the guide line
  const auto s = glide.inverse(singular);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_DOUBLE_EQ((*s)[0], 7.0);
  const auto j = glide.jacobian(singular);
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error().code, ErrorCode::singular);
  EXPECT_NE(j.error().message.find("carriage 1"), std::string::npos) << j.error().message;
  EXPECT_EQ(glide.guide_conditioning(singular), 0.0);
}

// An example machine file without the top-level lines that start with any of `keys`.
std::string example_without(const char* relative_path, std::initializer_list<const char*> keys) {
  std::ifstream in(test::source_path(relative_path));
  std::string text, line;
  while (std::getline(in, line)) {
    bool drop = false;
    for (const char* key : keys) drop = drop || line.rfind(key, 0) == 0;
    if (!drop) text += line + "\n";
  }
  return text;
}

TEST(GlideFile, DefaultBranchIsTheRootNearerTheGuidePoint) {
  for (const char* home : {"home: [0, 0, 350, 0, 0, 0]\n", "home: [40, -30, 380, 3, -2, 5]\n"}) {
    const Machine m = test::machine_from_text(
        example_without("examples/machines/hexaglide.yaml", {"branch:", "home:", "limits:"}) + home);
    const Glide& glide = as_glide(m);
    GlideGeometry flipped = glide.geometry();
    for (int j = 0; j < 6; ++j) flipped.branches[j] = -flipped.branches[j];
    const Glide other(flipped, AngleConvention::abc, glide.home());
    const auto s = glide.inverse(glide.home());
    const auto t = other.inverse(glide.home());
    ASSERT_TRUE(s.ok() && t.ok());
    for (int j = 0; j < 6; ++j) EXPECT_LE(std::abs((*s)[j]), std::abs((*t)[j])) << "carriage " << j + 1;
  }
}

TEST(GlideFile, DefaultHomeIsLevelAndNonSingular) {
  for (const char* file : {"examples/machines/triglide.yaml", "examples/machines/hexaglide.yaml"}) {
    const Machine m = test::machine_from_text(example_without(file, {"home:", "limits:"}));
    const Glide& glide = as_glide(m);
    EXPECT_FALSE(m.home_given);
    EXPECT_LT((glide.home().rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
    // Struts near 45° to their guides, far from the inverse singularity; the platform under the guides.
    EXPECT_GT(glide.guide_conditioning(glide.home()), 0.4) << file;
    EXPECT_LT(glide.home().position_mm.z(), glide.geometry().guide_points_mm[0].z()) << file;
    expect_jacobian_matches_finite_differences(glide, glide.home());
  }
}

std::string glide_error_of(const std::string& yaml, const std::string& name) {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok());
  return machine.ok() ? std::string() : machine.error().message;
}

// Lines: 1 type, 2 angles, 3 guides, 4-6 guides, 7 strut_lengths, 8 platform_joints, 9 home.
constexpr const char* kTriglideGuides = R"(type: glide
angles: abc
guides:
  - {point: [0, 500, 800], direction: [0, -0.5, 0.8660254037844386]}
  - {point: [-433.0127, -250, 800], direction: [0.4330127, 0.25, 0.8660254]}
  - {point: [433.0127, -250, 800], direction: [-0.4330127, 0.25, 0.8660254]}
)";

TEST(GlideFile, ErrorsNameFileLineAndKey) {
  const std::string joints = "platform_joints: [[0, 80, 0], [-69.282, -40, 0], [69.282, -40, 0]]\n";
  // Missing strut_lengths.
  std::string message = glide_error_of(std::string(kTriglideGuides) + joints, "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:1:1: strut_lengths: missing"), std::string::npos) << message;
  // Misspelt top-level key (line 7).
  message =
      glide_error_of(std::string(kTriglideGuides) + "strut_length: [600, 600, 600]\n" + joints, "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:7:1: strut_length: unknown key"), std::string::npos) << message;
  // Wrong count (line 7): 2 lengths for 3 guides.
  message = glide_error_of(std::string(kTriglideGuides) + "strut_lengths: [600, 600]\n" + joints, "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:7:16: strut_lengths: expected a list of 3 numbers, got 2"),
            std::string::npos)
      << message;
  // Wrong count of platform joints (line 8).
  message = glide_error_of(
      std::string(kTriglideGuides) + "strut_lengths: [600, 600, 600]\nplatform_joints: [[0, 0, 0]]\n",
      "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:8:18: platform_joints: expected a list of 3 points"), std::string::npos)
      << message;
  // Misspelt guide key (line 5).
  std::string yaml = kTriglideGuides;
  yaml.replace(yaml.find("direction: [0.4330127"), 9, "dirction");
  message = glide_error_of(yaml + "strut_lengths: [600, 600, 600]\n" + joints, "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:5:37: guides[1].dirction: unknown key"), std::string::npos) << message;
  // Four guides (line 4: the list starts there).
  message = glide_error_of(
      "type: glide\nangles: abc\nguides:\n  - {point: [0, 0, 0], direction: [1, 0, 0]}\n"
      "  - {point: [0, 0, 0], direction: [1, 0, 0]}\n  - {point: [0, 0, 0], direction: [1, 0, 0]}\n"
      "  - {point: [0, 0, 0], direction: [1, 0, 0]}\n",
      "four.yaml");
  EXPECT_NE(message.find("four.yaml:4:3: guides: expected a list of 3 or 6 guides"), std::string::npos)
      << message;
  // Zero direction, bad branch value, angles on a three-guide home.
  yaml = kTriglideGuides;
  yaml.replace(yaml.find("[0, -0.5, 0.8660254037844386]"), 29, "[0, 0, 0]");
  message = glide_error_of(yaml + "strut_lengths: [600, 600, 600]\n" + joints, "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:4:39: guides[0].direction: a guide direction must not be zero"),
            std::string::npos)
      << message;
  message = glide_error_of(
      std::string(kTriglideGuides) + "strut_lengths: [600, 600, 600]\n" + joints + "branch: [1, 2, 1]\n",
      "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:9:13: branch[1]: expected +1 or -1, got 2"), std::string::npos) << message;
  message = glide_error_of(std::string(kTriglideGuides) + "strut_lengths: [600, 600, 600]\n" + joints +
                               "home: [0, 0, 300, 0, 5, 0]\n",
                           "tri.yaml");
  EXPECT_NE(message.find("tri.yaml:9:7: home: a three-guide glide keeps its platform orientation fixed"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace pkm
