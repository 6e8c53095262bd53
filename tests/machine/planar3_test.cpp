// Planar 3-RPR platform against Smirnov 2019, §3.3 (Fig. 70; the layout of §3.3–3.4) and property tests.
#include "machine/planar3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "core/units.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Pose planar_pose(double x_mm, double y_mm, double phi_deg) {
  return pose_from_planar(Eigen::Vector3d(x_mm, y_mm, rad_from_deg(phi_deg)));
}

/// det J* of eq. (82), the Jacobian of the squared lengths: 8·L1·L2·L3·det J (Smirnov 2019, §3.3), mm⁴.
double squared_length_determinant(const Mechanism& mechanism, const Pose& pose) {
  const ActuatorVector q = *mechanism.inverse(pose);
  return 8.0 * q[0] * q[1] * q[2] * Eigen::Matrix3d(*mechanism.jacobian(pose)).determinant();
}

/// The layout of Smirnov 2019, §3.3–3.4: A_j on R = 200 mm and B'_j on R = 100 mm at the same polar angles.
Planar3Geometry uniform_geometry(double first_angle_deg) {
  Planar3Geometry g;
  for (int j = 0; j < 3; ++j) {
    const double t = rad_from_deg(first_angle_deg + 120.0 * j);
    g.base_joints_mm[j] = 200.0 * Eigen::Vector2d(std::cos(t), std::sin(t));
    g.platform_joints_mm[j] = 100.0 * Eigen::Vector2d(std::cos(t), std::sin(t));
  }
  return g;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Random base (spread 150…400 mm) and platform (spread 40…150 mm) triangles that are not nearly flat.
Planar3Geometry planar3_random_geometry(std::mt19937_64& rng) {
  Planar3Geometry g;
  auto area = [](const std::array<Eigen::Vector2d, 3>& p) {
    return 0.5 * std::abs(cross(p[1] - p[0], p[2] - p[0]));
  };
  do {
    const double base_mm = test::uniform(rng, 150, 400), platform_mm = test::uniform(rng, 40, 150);
    for (int j = 0; j < 3; ++j) {
      g.base_joints_mm[j] = {test::uniform(rng, -base_mm, base_mm), test::uniform(rng, -base_mm, base_mm)};
      g.platform_joints_mm[j] = {test::uniform(rng, -platform_mm, platform_mm),
                                 test::uniform(rng, -platform_mm, platform_mm)};
    }
  } while (area(g.base_joints_mm) < 5000.0 || area(g.platform_joints_mm) < 800.0);
  return g;
}

std::string planar3_yaml(const std::string& platform, const std::string& extra = "") {
  return "type: planar3\n"
         "base_joints:\n"
         "  - [0, 200]\n"
         "  - [-173.20508075688772, -100]\n"
         "  - [173.20508075688772, -100]\n"
         "platform_joints:\n" +
         platform + extra;
}
const std::string kUniformPlatform =
    "  - [0, 100]\n  - [-86.60254037844386, -50]\n  - [86.60254037844386, -50]\n";

std::string planar3_load_error(const std::string& yaml, const std::string& name = "bad.yaml") {
  auto machine = parse_machine_text(yaml, name);
  EXPECT_FALSE(machine.ok()) << "expected " << name << " to be rejected";
  return machine ? std::string() : machine.error().message;
}

/// Checks forward_all at the lengths of `truth`: every solution fits, at most six, and one is `truth`.
void expect_assembly_modes_contain(const Planar3& mechanism, const Pose& truth,
                                   const FkOptions& options = {}) {
  const ActuatorVector q = *mechanism.inverse(truth);
  const auto all = mechanism.forward_all(q, options);
  ASSERT_TRUE(all.ok()) << all.error().message;
  ASSERT_LE(all->size(), 6u);
  bool found = false;
  for (const auto& s : *all) {
    EXPECT_LE(((*mechanism.inverse(s.pose)) - q).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LE(s.residual_mm, 1e-9);
    const PoseDistance d = pose_distance(s.pose, truth);
    found = found || (d.position_mm < 1e-6 && d.rotation_rad < 1e-8);
  }
  const Eigen::Vector3d c = planar_coordinates(truth);
  EXPECT_TRUE(found) << "forward_all misses (" << c.x() << ", " << c.y() << ", " << deg_from_rad(c.z())
                     << " deg)";
}

TEST(Planar3V2, SquaredLengthJacobianDeterminantValues) {
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  // §3.3, Fig. 70: x_C = −10 mm, y_C = 10 mm; the overall sign depends on the row/column order, so compare
  // magnitudes.
  const double expected[3][2] = {{-20, 1.736e9}, {-40, 5.119e9}, {-60, 1.073e10}};
  for (const auto& [phi_deg, magnitude] : expected) {
    const double det_minus = squared_length_determinant(*m.mechanism, planar_pose(-10, 10, phi_deg));
    const double det_plus = squared_length_determinant(*m.mechanism, planar_pose(-10, 10, -phi_deg));
    EXPECT_NEAR(std::abs(det_minus), magnitude, 1e-3 * magnitude) << "phi = " << phi_deg;
    EXPECT_NEAR(det_plus, -det_minus, 1e-9 * magnitude) << "antisymmetric in phi";
  }
  EXPECT_NEAR(squared_length_determinant(*m.mechanism, planar_pose(-10, 10, 0)), 0.0, 1e-3);
}

TEST(Planar3V2, DeterminantChangesSignOnceAtZero) {
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  int changes = 0;
  double previous = squared_length_determinant(*m.mechanism, planar_pose(-10, 10, -60));
  double previous_phi = -60;
  for (double phi_deg = -59.75; phi_deg <= 60.0; phi_deg += 0.5) {
    const double det = squared_length_determinant(*m.mechanism, planar_pose(-10, 10, phi_deg));
    ASSERT_NE(det, 0.0);
    if ((det > 0) != (previous > 0)) {
      ++changes;
      EXPECT_LT(previous_phi, 0.0);
      EXPECT_GT(phi_deg, 0.0);
    }
    previous = det;
    previous_phi = phi_deg;
  }
  EXPECT_EQ(changes, 1);
}

TEST(Planar3V2, UniformLayoutIsSingularAtZeroAngleEverywhere) {
  const Planar3 mechanism(uniform_geometry(90), Eigen::Vector3d(0, 0, rad_from_deg(15)));
  for (const Eigen::Vector2d& c :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(-10, 10), Eigen::Vector2d(35, -20)}) {
    EXPECT_LT(std::abs(mechanism.normalized_determinant(Eigen::Vector3d(c.x(), c.y(), 0.0))), 1e-12);
  }
}

TEST(Planar3Property, InverseThenForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(77);
  for (int geometry_index = 0; geometry_index < 6; ++geometry_index) {
    // The first geometry is the ch3 uniform (similar-triangle) layout; the others are random.
    const Planar3Geometry g = geometry_index == 0 ? uniform_geometry(90) : planar3_random_geometry(rng);
    const Planar3 mechanism(g, Eigen::Vector3d(0, 0, rad_from_deg(15)));
    int tested = 0;
    while (tested < 1000) {
      const Eigen::Vector3d truth_c(test::uniform(rng, -100, 100), test::uniform(rng, -100, 100),
                                    rad_from_deg(test::uniform(rng, -60, 60)));
      if (std::abs(mechanism.normalized_determinant(truth_c)) < 0.05) continue;  // not near a singularity
      const Pose truth = pose_from_planar(truth_c);
      const ActuatorVector q = *mechanism.inverse(truth);
      if (q.minCoeff() < 10.0) continue;
      ++tested;
      const Eigen::Vector3d guess_c =
          truth_c + Eigen::Vector3d(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1),
                                    rad_from_deg(test::uniform(rng, -0.5, 0.5)));
      const auto fk = mechanism.forward(q, pose_from_planar(guess_c));
      ASSERT_TRUE(fk.ok()) << fk.error().message;
      EXPECT_LE(fk->residual_mm, 1e-9);
      EXPECT_LE(((*mechanism.inverse(fk->pose)) - q).cwiseAbs().maxCoeff(), 1e-9);
      const PoseDistance d = pose_distance(fk->pose, truth);
      EXPECT_LT(d.position_mm, 1e-7);
      EXPECT_LT(d.rotation_rad, 1e-9);
      expect_assembly_modes_contain(mechanism, truth);
    }
  }
}

TEST(Planar3Property, JacobianMatchesCentralFiniteDifferences) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 200; ++i) {
    const Planar3Geometry g = planar3_random_geometry(rng);
    const Planar3 mechanism(g, Eigen::Vector3d::Zero());
    const Eigen::Vector3d c(test::uniform(rng, -100, 100), test::uniform(rng, -100, 100),
                            rad_from_deg(test::uniform(rng, -90, 90)));
    const ActuatorVector q = *mechanism.inverse(pose_from_planar(c));
    if (q.minCoeff() < 20.0) continue;
    const auto j = mechanism.jacobian(pose_from_planar(c));
    ASSERT_TRUE(j.ok());
    ASSERT_EQ(j->rows(), 3);
    ASSERT_EQ(j->cols(), 3);
    for (int k = 0; k < 3; ++k) {
      const double h = k < 2 ? 1e-4 : 1e-6;  // mm, rad
      Eigen::Vector3d plus = c, minus = c;
      plus[k] += h;
      minus[k] -= h;
      const ActuatorVector dq =
          (*mechanism.inverse(pose_from_planar(plus)) - *mechanism.inverse(pose_from_planar(minus))) /
          (2 * h);
      for (int row = 0; row < 3; ++row) EXPECT_NEAR((*j)(row, k), dq[row], k < 2 ? 1e-7 : 1e-5);
    }
  }
}

TEST(Planar3AssemblyModes, RandomLayoutsReachSixModesAndNeverMore) {
  // Six is the classical bound for the planar 3-RPR (G has degree 3 in e^{iφ}); some random layouts reach it.
  std::mt19937_64 rng(3);
  int most = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Planar3Geometry g = planar3_random_geometry(rng);
    const Planar3 mechanism(g, Eigen::Vector3d::Zero());
    const Pose truth = pose_from_planar(Eigen::Vector3d(
        test::uniform(rng, -50, 50), test::uniform(rng, -50, 50), rad_from_deg(test::uniform(rng, -90, 90))));
    if (std::abs(mechanism.normalized_determinant(planar_coordinates(truth))) < 0.05) continue;
    const auto all = mechanism.forward_all(*mechanism.inverse(truth));
    ASSERT_TRUE(all.ok()) << all.error().message;
    ASSERT_LE(all->size(), 6u);
    most = std::max(most, static_cast<int>(all->size()));
    expect_assembly_modes_contain(mechanism, truth);
  }
  EXPECT_EQ(most, 6) << "no random layout reached the six assembly modes of the planar 3-RPR";
}

TEST(Planar3AssemblyModes, EveryModeAMultiStartSearchFindsIsEnumerated) {
  // Oracle independent of the elimination: Newton from many random starts over the whole workspace.
  std::mt19937_64 rng(8);
  FkOptions free_branch;
  free_branch.require_same_branch = false;
  for (int trial = 0; trial < 30; ++trial) {
    const Planar3 mechanism(planar3_random_geometry(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d truth(test::uniform(rng, -80, 80), test::uniform(rng, -80, 80),
                                test::uniform(rng, -3, 3));
    const ActuatorVector q = *mechanism.inverse(pose_from_planar(truth));
    const auto all = mechanism.forward_all(q);
    ASSERT_TRUE(all.ok()) << all.error().message;
    for (int start = 0; start < 400; ++start) {
      const Eigen::Vector3d s(test::uniform(rng, -600, 600), test::uniform(rng, -600, 600),
                              test::uniform(rng, -kPi, kPi));
      const auto found = mechanism.solve_from(q, s, free_branch);
      if (!found) continue;
      bool listed = false;
      for (const auto& known : *all) {
        const PoseDistance d = pose_distance(known.pose, found->pose);
        listed = listed || (d.position_mm < 1e-6 && d.rotation_rad < 1e-8);
      }
      const Eigen::Vector3d c = planar_coordinates(found->pose);
      EXPECT_TRUE(listed) << "trial " << trial << ": (" << c.x() << ", " << c.y() << ", "
                          << deg_from_rad(c.z()) << " deg) is missing from forward_all";
    }
  }
}

TEST(Planar3AssemblyModes, SimilarTrianglesFindBothMirrorModes) {
  // The layout of Smirnov 2019, §3.3–3.4: at x = y = 0 the lengths are even in φ, so φ and −φ are two
  // assembly modes of opposite sign of det J. The elimination still works although the base and platform
  // triangles are similar.
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  const ActuatorVector q = *m.mechanism->inverse(planar_pose(0, 0, 15));
  const auto all = m.mechanism->forward_all(q);
  ASSERT_TRUE(all.ok()) << all.error().message;
  ASSERT_GE(all->size(), 2u);
  EXPECT_LT(pose_distance((*all)[0].pose, planar_pose(0, 0, 15)).position_mm, 1e-9);  // home first
  EXPECT_EQ((*all)[0].branch, 0);
  bool mirror = false;
  for (const auto& s : *all) {
    const PoseDistance d = pose_distance(s.pose, planar_pose(0, 0, -15));
    if (d.position_mm < 1e-6 && d.rotation_rad < 1e-9) {
      mirror = true;
      EXPECT_EQ(s.branch, 1);
    }
  }
  EXPECT_TRUE(mirror);
  // The circle of §3.4.1 (R = 40 mm about O at φ = 15°) and poses on both sides of the singular φ = 0.
  const auto& mechanism = dynamic_cast<const Planar3&>(*m.mechanism);
  for (int step = 0; step < 360; step += 5) {
    const double t = rad_from_deg(step);
    expect_assembly_modes_contain(mechanism, planar_pose(40 * std::cos(t), 40 * std::sin(t), 15));
    expect_assembly_modes_contain(mechanism, planar_pose(40 * std::cos(t), 40 * std::sin(t), -30));
  }
}

TEST(Planar3AssemblyModes, EliminationDeterminantVanishingAtTheSolution) {
  // Base joints A_j = R(φ*) b'_j + s_j w make every row of M(φ*) parallel to w, so det M(φ*) = 0 exactly at
  // the true angle: C must then come from the circle pairs, not from adj(M) r / det M.
  Planar3Geometry g;
  g.platform_joints_mm = {Eigen::Vector2d(60, 0), Eigen::Vector2d(-30, 50), Eigen::Vector2d(-30, -50)};
  const double phi_star = rad_from_deg(25);
  const Eigen::Vector2d w(1, 0.3);
  const double s[3] = {0, 120, -90};
  for (int j = 0; j < 3; ++j)
    g.base_joints_mm[j] = Eigen::Rotation2Dd(phi_star) * g.platform_joints_mm[j] + s[j] * w;
  const Planar3 mechanism(g, Eigen::Vector3d(40, 150, phi_star));
  for (const Eigen::Vector2d& c :
       {Eigen::Vector2d(40, 150), Eigen::Vector2d(-70, 90), Eigen::Vector2d(10, -120)}) {
    const Eigen::Vector3d truth(c.x(), c.y(), phi_star);
    ASSERT_GT(std::abs(mechanism.normalized_determinant(truth)), 1e-3)
        << "the test pose itself must be regular";
    expect_assembly_modes_contain(mechanism, pose_from_planar(truth));
  }
}

TEST(Planar3AssemblyModes, CongruentTrianglesWhereTheEliminationMatrixVanishes) {
  // Platform = base triangle: M(0) = 0, and at φ = 0 all struts are parallel and equal (a continuum of poses,
  // architecture singularity). Away from φ = 0 every mode is found; at φ = 0 FK reports the singularity.
  Planar3Geometry g = uniform_geometry(90);
  g.platform_joints_mm = g.base_joints_mm;
  const Planar3 mechanism(g, Eigen::Vector3d(0, 0, rad_from_deg(20)));
  for (double phi_deg : {-40.0, -5.0, 0.5, 20.0, 70.0}) {
    expect_assembly_modes_contain(mechanism, planar_pose(30, 40, phi_deg));
  }
  const Pose parallel = planar_pose(30, 40, 0);
  const auto fk = mechanism.forward(*mechanism.inverse(parallel), parallel);
  ASSERT_FALSE(fk.ok());
  EXPECT_EQ(fk.error().code, ErrorCode::singular) << fk.error().message;
}

TEST(Planar3Branch, MirrorGuessGivesTheMirrorMode) {
  // Uniform layout: the lengths of (5, −3, −20°) also fit a φ > 0 pose; a guess with φ < 0 stays with φ < 0,
  // the mode of the other sign of det J than home (15°), so branch 1.
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  const ActuatorVector q = *m.mechanism->inverse(planar_pose(5, -3, -20));
  const auto mirror = m.mechanism->forward(q, planar_pose(4, -2, -18));
  ASSERT_TRUE(mirror.ok()) << mirror.error().message;
  EXPECT_LT(pose_distance(mirror->pose, planar_pose(5, -3, -20)).position_mm, 1e-9);
  EXPECT_EQ(mirror->branch, 1);
  const auto home_mode =
      m.mechanism->forward(*m.mechanism->inverse(planar_pose(5, -3, 20)), m.mechanism->home());
  ASSERT_TRUE(home_mode.ok());
  EXPECT_EQ(home_mode->branch, 0);
}

TEST(Planar3Branch, CrossingToTheOtherSignOfDetJIsAWrongBranchError) {
  // Far guesses on random layouts sometimes converge across a singularity. Without the same-branch rule the
  // solution is returned; with it (the default) the same call must fail with wrong_branch.
  std::mt19937_64 rng(1);
  FkOptions free_branch;
  free_branch.require_same_branch = false;
  int crossings = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Planar3 mechanism(planar3_random_geometry(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d truth(test::uniform(rng, -80, 80), test::uniform(rng, -80, 80),
                                test::uniform(rng, -1, 1));
    const Eigen::Vector3d guess =
        truth + Eigen::Vector3d(test::uniform(rng, -60, 60), test::uniform(rng, -60, 60),
                                test::uniform(rng, -0.8, 0.8));
    if (std::abs(mechanism.normalized_determinant(guess)) < 1e-3) continue;
    const ActuatorVector q = *mechanism.inverse(pose_from_planar(truth));
    const auto free = mechanism.forward(q, pose_from_planar(guess), free_branch);
    if (!free ||
        mechanism.determinant_sign(planar_coordinates(free->pose)) == mechanism.determinant_sign(guess)) {
      continue;
    }
    ++crossings;
    const auto strict = mechanism.forward(q, pose_from_planar(guess));
    ASSERT_FALSE(strict.ok());
    EXPECT_EQ(strict.error().code, ErrorCode::wrong_branch);
    EXPECT_NE(strict.error().message.find("another assembly mode"), std::string::npos);
  }
  EXPECT_GT(crossings, 0) << "the search found no crossing to test";
}

TEST(Planar3Errors, UnreachableLengths) {
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  ActuatorVector q(3);
  q << 1.0, 1.0, 1.0;  // the platform (side 173 mm) cannot reach base joints 346 mm apart
  const auto all = m.mechanism->forward_all(q);
  ASSERT_FALSE(all.ok());
  EXPECT_EQ(all.error().code, ErrorCode::unreachable);
  EXPECT_NE(all.error().message.find("1.000000"), std::string::npos) << all.error().message;
  const auto fk = m.mechanism->forward(q, m.mechanism->home());
  ASSERT_FALSE(fk.ok());
  EXPECT_EQ(fk.error().code, ErrorCode::unreachable) << fk.error().message;
  q << 2000.0, 10.0, 10.0;
  const auto far = m.mechanism->forward(q, m.mechanism->home());
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(far.error().code, ErrorCode::unreachable) << far.error().message;
}

TEST(Planar3Errors, SingularLengthsAreReported) {
  // Uniform layout at φ = 0: singular at every (x, y); FK there must say so, not return a pose.
  const Machine m = test::machine_from_example("examples/machines/planar3.yaml");
  const ActuatorVector q = *m.mechanism->inverse(planar_pose(-10, 10, 0));
  const auto fk = m.mechanism->forward(q, planar_pose(-10, 10, 0));
  ASSERT_FALSE(fk.ok());
  EXPECT_EQ(fk.error().code, ErrorCode::singular) << fk.error().message;
}

TEST(Planar3MachineFile, ToolPointIsThePoseOrigin) {
  const Machine plain = test::machine_from_text(planar3_yaml(kUniformPlatform, "home: [0, 0, 15]\n"));
  const Machine tooled =
      test::machine_from_text(planar3_yaml(kUniformPlatform, "tool: [10, 5]\nhome: [0, 0, 15]\n"));
  // The platform pose (x, y, φ) puts the tool at (x, y) + R(φ)·(10, 5).
  const Eigen::Vector2d tool = Eigen::Rotation2Dd(rad_from_deg(30)) * Eigen::Vector2d(10, 5);
  const ActuatorVector a = *plain.mechanism->inverse(planar_pose(7, -4, 30));
  const ActuatorVector b = *tooled.mechanism->inverse(planar_pose(7 + tool.x(), -4 + tool.y(), 30));
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(controlled_coordinate_names(*plain.mechanism), (std::vector<std::string>{"x", "y", "phi"}));
}

TEST(Planar3MachineFile, DefaultHomeAvoidsTheSingularZeroAngle) {
  const Machine m = test::machine_from_text(planar3_yaml(kUniformPlatform));
  EXPECT_FALSE(m.home_given);
  const Eigen::Vector3d home = planar_coordinates(m.mechanism->home());
  EXPECT_NEAR(home.x(), 0.0, 1e-9);
  EXPECT_NEAR(home.y(), 0.0, 1e-9);
  EXPECT_NE(home.z(), 0.0);
  const auto& mechanism = dynamic_cast<const Planar3&>(*m.mechanism);
  EXPECT_GT(std::abs(mechanism.normalized_determinant(home)), 0.05);
}

TEST(Planar3MachineFile, ErrorsNameFileLineAndKey) {
  EXPECT_NE(planar3_load_error("type: planar3\nbase_joints:\n  - [0, 0]\n  - [1, 0]\n  - [0, 1]\n")
                .find("bad.yaml:1:1: platform_joints: missing"),
            std::string::npos);
  EXPECT_NE(planar3_load_error(planar3_yaml(kUniformPlatform, "platfrom_joint: 3\n"))
                .find("bad.yaml:10:1: platfrom_joint: unknown key"),
            std::string::npos);
  EXPECT_NE(
      planar3_load_error(planar3_yaml("  - [0, 100]\n  - [1, 2]\n"))
          .find("bad.yaml:7:3: platform_joints: expected a list of 3 points of 2 numbers, got 2 points"),
      std::string::npos);
  EXPECT_NE(planar3_load_error(planar3_yaml("  - [0, 100]\n  - [1, 2, 3]\n  - [4, 5]\n"))
                .find("bad.yaml:8:5: platform_joints[1]: expected 2 numbers, got 3"),
            std::string::npos);
  EXPECT_NE(planar3_load_error(planar3_yaml(kUniformPlatform, "home: [0, 0]\n"))
                .find("bad.yaml:10:7: home: expected a list of 3 numbers, got 2"),
            std::string::npos);
  EXPECT_NE(planar3_load_error(planar3_yaml(kUniformPlatform, "home: [0, 0, 0]\n"))
                .find("bad.yaml:10:7: home: planar3 is singular"),
            std::string::npos);
  EXPECT_NE(planar3_load_error(planar3_yaml(kUniformPlatform, "tool: [1, 2, 3]\n"))
                .find("bad.yaml:10:7: tool: expected 2 numbers, got 3"),
            std::string::npos);
  EXPECT_NE(
      planar3_load_error(planar3_yaml(kUniformPlatform, "angles: abc\n")).find("bad.yaml:10:9: angles:"),
      std::string::npos);
}

}  // namespace
}  // namespace pkm
