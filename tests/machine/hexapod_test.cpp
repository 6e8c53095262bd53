// Hexapod kinematics against the dissertation's numbers (Smirnov 2019, §5.2.5) and property tests.
#include "machine/hexapod.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <random>

#include "core/units.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Pose hexapod_krylov_pose(double x, double y, double z, double psi_deg, double theta_deg, double gamma_deg) {
  PoseVector c;
  c << x, y, z, rad_from_deg(psi_deg), rad_from_deg(theta_deg), rad_from_deg(gamma_deg);
  return pose_from_vector(AngleConvention::krylov, c);
}

TEST(HexapodCh5, E2StrutLengthsAtStartPose) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto lengths = m.mechanism->inverse(hexapod_krylov_pose(-50, 0, 700, 0, 0, 0));
  ASSERT_TRUE(lengths.ok());
  const double expected[6] = {623.7911728445, 607.5487036598, 603.1222458757,
                              586.3074649620, 588.5880863511, 621.6397151039};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR((*lengths)[j], expected[j], 1e-9) << "strut " << j + 1;
}

TEST(HexapodCh5, DerivedValidationVectors) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  struct Case {
    Pose pose;
    double lengths[6];
  };
  const Case cases[] = {
      {hexapod_krylov_pose(50, 0, 700, 0, 0, 0),
       {586.3074649620, 603.1222458757, 607.5487036599, 623.7911728446, 621.6397151039, 588.5880863511}},
      {hexapod_krylov_pose(0, 0, 700, 0, 0, 0),
       {603.2710297988, 603.2710297988, 603.2710297988, 603.2710297988, 603.2710297988, 603.2710297988}},
      {hexapod_krylov_pose(0, 0, 500, 0, 0, 0),
       {428.8775295985, 428.8775295985, 428.8775295985, 428.8775295985, 428.8775295985, 428.8775295985}},
      {hexapod_krylov_pose(10, -20, 650, 5, -3, 2),
       {554.9838565140, 580.7906869557, 558.4217904139, 568.8122903499, 545.4392839872, 546.5444035422}},
  };
  for (const Case& c : cases) {
    const auto lengths = m.mechanism->inverse(c.pose);
    ASSERT_TRUE(lengths.ok());
    for (int j = 0; j < 6; ++j) EXPECT_NEAR((*lengths)[j], c.lengths[j], 2e-10) << "strut " << j + 1;
  }
}

TEST(HexapodCh5, E3TruncatedLengthsGiveThePrintedPoseAndContourError) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  ActuatorVector truncated(6);
  truncated << 623.791, 607.548, 603.122, 586.307, 588.588, 621.639;
  const auto fk = m.mechanism->forward(truncated, hexapod_krylov_pose(-50, 0, 700, 0, 0, 0));
  ASSERT_TRUE(fk.ok()) << fk.error().message;
  const PoseVector c = vector_from_pose(AngleConvention::krylov, fk->pose);
  // Printed: (-49.9997, 2.6542e-4, 699.9996, -1.9999e-4, -6.3184e-6, 4.6194e-6), angles in degrees.
  EXPECT_NEAR(c[0], -49.99972591, 1e-7);
  EXPECT_NEAR(c[1], 2.6545e-4, 1e-8);
  EXPECT_NEAR(c[2], 699.99958614, 1e-7);
  EXPECT_NEAR(deg_from_rad(c[3]), -1.99990e-4, 1e-9);
  EXPECT_NEAR(deg_from_rad(c[4]), -6.31872e-6, 1e-10);
  EXPECT_NEAR(deg_from_rad(c[5]), 4.61938e-6, 1e-10);
  // Contour error of the X-directed line: the perpendicular offset sqrt(dy^2 + dz^2), printed 4.9166e-4 mm.
  const double contour_error_mm = std::hypot(c[1] - 0.0, c[2] - 700.0);
  // We get 4.91676e-4 mm; the printed 4.9166e-4 differs by 1.6e-8 mm (3e-5 relative), as an independent
  // recomputation also finds.
  EXPECT_NEAR(contour_error_mm, 4.9166e-4, 2e-8);
  EXPECT_LE(fk->residual_mm, 1e-9);
}

TEST(HexapodCh5, Struts2And3ReverseOnTheStandardLine) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto& hexapod = dynamic_cast<const Hexapod&>(*m.mechanism);
  double min_l2 = 1e9, x_at_min = 0;
  for (int i = 0; i <= 100000; ++i) {
    const double x = -50 + 100.0 * i / 100000;
    double l[6];
    hexapod.strut_lengths(hexapod_krylov_pose(x, 0, 700, 0, 0, 0), l);
    if (l[1] < min_l2) {
      min_l2 = l[1];
      x_at_min = x;
    }
  }
  EXPECT_NEAR(min_l2, 602.675674, 1e-6);
  EXPECT_NEAR(x_at_min, 26.79, 0.01);
}

// Random 6-6 geometries: base joints on a circle with jitter, platform joints likewise, random tool offset.
std::string random_hexapod_yaml(std::mt19937_64& rng, const char* angles) {
  const double base_radius = test::uniform(rng, 250, 600);
  const double platform_radius = test::uniform(rng, 0.3, 0.7) * base_radius;
  const double pair_half_angle = test::uniform(rng, 5, 25);
  std::string yaml = std::string("type: hexapod\nangles: ") + angles + "\nbase_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double a = rad_from_deg(60.0 * j + test::uniform(rng, -5, 5));
    yaml += "  - [" + std::to_string(base_radius * std::cos(a)) + ", " +
            std::to_string(base_radius * std::sin(a)) + ", " + std::to_string(test::uniform(rng, -10, 10)) +
            "]\n";
  }
  yaml += "platform_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const int pair = j / 2;
    const double centre = 120.0 * pair + 30.0;
    const double a =
        rad_from_deg(centre + (j % 2 == 0 ? -1 : 1) * pair_half_angle + test::uniform(rng, -3, 3));
    yaml += "  - [" + std::to_string(platform_radius * std::cos(a)) + ", " +
            std::to_string(platform_radius * std::sin(a)) + ", " + std::to_string(test::uniform(rng, -5, 5)) +
            "]\n";
  }
  const double tool_z = test::uniform(rng, 0, 250);
  yaml += "tool: [" + std::to_string(test::uniform(rng, -20, 20)) + ", " +
          std::to_string(test::uniform(rng, -20, 20)) + ", " + std::to_string(tool_z) + "]\n";
  // Home: the platform-joint plane 0.6..1.1 base radii above the base, the tool point tool_z above that.
  yaml +=
      "home: [0, 0, " + std::to_string(tool_z + base_radius * test::uniform(rng, 0.6, 1.1)) + ", 0, 0, 0]\n";
  return yaml;
}

TEST(HexapodProperty, InverseThenForwardRoundTripsOnRandomGeometries) {
  std::mt19937_64 rng(20261121);
  for (const char* angles : {"abc", "krylov", "euler_zxz"}) {
    for (int g = 0; g < 5; ++g) {
      const Machine m = test::machine_from_text(random_hexapod_yaml(rng, angles));
      const Pose home = m.mechanism->home();
      const auto& hexapod = dynamic_cast<const Hexapod&>(*m.mechanism);
      const double home_det = hexapod.twist_jacobian(home).determinant();
      double platform_radius = 0;
      for (const auto& b : hexapod.geometry().platform_joints_mm) platform_radius += b.head<2>().norm() / 6;
      int accepted = 0, skipped = 0;
      while (accepted < 1000 && skipped < 2000) {
        PoseVector c = vector_from_pose(m.mechanism->convention(), home);
        if (m.mechanism->convention() == AngleConvention::euler_zxz) {
          // Tilt 3..10° about a random horizontal axis (away from the nutation singularity at 0), with the
          // platform's net spin psi + phi within ±10° like the other conventions.
          const double precession = test::uniform(rng, -kPi, kPi);
          c.tail<3>() = Eigen::Vector3d(precession, rad_from_deg(test::uniform(rng, 3, 10)),
                                        -precession + rad_from_deg(test::uniform(rng, -10, 10)));
        } else {
          for (int k = 3; k < 6; ++k) c[k] = rad_from_deg(test::uniform(rng, -10, 10));
        }
        for (int k = 0; k < 3; ++k) c[k] += test::uniform(rng, -50, 50);
        const Pose truth = pose_from_vector(m.mechanism->convention(), c);
        // Random geometries and tilts reach singular surfaces; near one, distinct solutions lie millimetres
        // apart and "the" pose is not defined. Poses across a singularity from home, or within a small
        // singular value (mm per rad or mm per mm) of one, are skipped and counted. The angular columns are
        // scaled by the platform radius so that all singular values are dimensionless.
        Eigen::Matrix<double, 6, 6> j_truth = hexapod.twist_jacobian(truth);
        j_truth.rightCols<3>() /= platform_radius;
        if (j_truth.determinant() * home_det <= 0 ||
            Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>>(j_truth).singularValues()[5] < 0.05) {
          ++skipped;
          continue;
        }
        ++accepted;
        const auto lengths = m.mechanism->inverse(truth);
        ASSERT_TRUE(lengths.ok());
        // Warm start from a guess a few mm and degrees away.
        Pose guess = truth;
        guess.position_mm +=
            Eigen::Vector3d(test::uniform(rng, -3, 3), test::uniform(rng, -3, 3), test::uniform(rng, -3, 3));
        guess.rotation =
            rotation_from_rotation_vector(Eigen::Vector3d::Constant(rad_from_deg(1))) * guess.rotation;
        const auto fk = m.mechanism->forward(*lengths, guess);
        ASSERT_TRUE(fk.ok()) << fk.error().message;
        const PoseDistance d = pose_distance(fk->pose, truth);
        // Round trip in actuator space to 1e-9 mm; the pose then follows to within the error amplification.
        EXPECT_LE(fk->residual_mm, 1e-9);
        EXPECT_LT(d.position_mm, 1e-8);
        EXPECT_LT(d.rotation_rad, 1e-10);
        const PoseVector back = vector_from_pose(m.mechanism->convention(), fk->pose);
        for (int k = 3; k < 6; ++k) EXPECT_LT(std::abs(std::remainder(back[k] - c[k], 2 * kPi)), 1e-10);
      }
      EXPECT_EQ(accepted, 1000);
      EXPECT_LT(skipped, 1000) << "most samples near-singular: the generator is off";
    }
  }
}

TEST(HexapodProperty, JacobianMatchesFiniteDifferences) {
  std::mt19937_64 rng(5);
  for (const char* angles : {"abc", "krylov", "euler_zxz"}) {
    const Machine m = test::machine_from_text(random_hexapod_yaml(rng, angles));
    PoseVector c = vector_from_pose(m.mechanism->convention(), m.mechanism->home());
    c += (PoseVector() << 12, -7, 20, 0.1, 0.2, -0.15).finished();
    const auto j = m.mechanism->jacobian(pose_from_vector(m.mechanism->convention(), c));
    ASSERT_TRUE(j.ok());
    for (int k = 0; k < 6; ++k) {
      const double h = k < 3 ? 1e-4 : 1e-7;
      PoseVector cp = c, cm = c;
      cp[k] += h;
      cm[k] -= h;
      const auto lp = m.mechanism->inverse(pose_from_vector(m.mechanism->convention(), cp));
      const auto lm = m.mechanism->inverse(pose_from_vector(m.mechanism->convention(), cm));
      const ActuatorVector fd = (*lp - *lm) / (2 * h);
      EXPECT_LT((fd - j->col(k)).cwiseAbs().maxCoeff(), 1e-5 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
          << angles << " column " << k;
    }
  }
}

TEST(HexapodAssemblyModes, SixThreeEnumerationContainsTheTruePoseAndOnlySolutions) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20; ++i) {
    const Pose truth = hexapod_krylov_pose(test::uniform(rng, -60, 60), test::uniform(rng, -60, 60),
                                           test::uniform(rng, 620, 760), test::uniform(rng, -15, 15),
                                           test::uniform(rng, -15, 15), test::uniform(rng, -15, 15));
    const auto lengths = m.mechanism->inverse(truth);
    const auto all = m.mechanism->forward_all(*lengths);
    ASSERT_TRUE(all.ok()) << all.error().message;
    EXPECT_GE(all->size(), 2u);  // the pose and at least its mirror image through the base plane
    EXPECT_LE(all->size(), 16u);
    bool found = false;
    for (const auto& s : *all) {
      const auto back = m.mechanism->inverse(s.pose);
      EXPECT_LT((*back - *lengths).cwiseAbs().maxCoeff(), 1e-9);
      const PoseDistance d = pose_distance(s.pose, truth);
      found = found || (d.position_mm < 1e-8 && d.rotation_rad < 1e-10);
    }
    EXPECT_TRUE(found);
    const PoseDistance first = pose_distance(all->front().pose, truth);
    EXPECT_LT(first.position_mm, 1e-8) << "the home-side solution comes first";
    EXPECT_EQ(all->front().branch, 0);
  }
}

TEST(HexapodAssemblyModes, MirroredSolutionIsReportedNotReturnedAsSuccess) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Pose truth = hexapod_krylov_pose(10, 5, 700, 2, 1, -3);
  const auto lengths = m.mechanism->inverse(truth);
  // Start below the base plane: Newton converges to the mirror image, which must be rejected.
  Pose mirror_guess = truth;
  mirror_guess.position_mm.z() = -700;
  mirror_guess.rotation = rot_x(kPi) * truth.rotation;
  const auto fk = m.mechanism->forward(*lengths, mirror_guess);
  ASSERT_FALSE(fk.ok());
  EXPECT_EQ(fk.error().code, ErrorCode::wrong_branch);
  FkOptions any_branch;
  any_branch.require_same_branch = false;
  const auto mirrored = m.mechanism->forward(*lengths, mirror_guess, any_branch);
  ASSERT_TRUE(mirrored.ok());
  EXPECT_NE(mirrored->branch, 0);
}

TEST(HexapodErrors, SingularJacobianIsReported) {
  // A planar configuration: all platform joints in the base plane makes every strut horizontal.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  Pose flat = hexapod_krylov_pose(0, 0, 150, 0, 0, 0);  // joint plane at z = 0, the base plane
  const auto lengths = m.mechanism->inverse(flat);
  ASSERT_TRUE(lengths.ok());
  const auto fk = m.mechanism->forward(*lengths, flat);
  ASSERT_FALSE(fk.ok());
  EXPECT_EQ(fk.error().code, ErrorCode::singular);
}

TEST(HexapodErrors, NonConvergenceIsReported) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  ActuatorVector impossible(6);
  impossible << 100, 1000, 100, 1000, 100, 1000;
  FkOptions options;
  options.max_iterations = 30;
  const auto fk = m.mechanism->forward(impossible, m.mechanism->home(), options);
  ASSERT_FALSE(fk.ok());
  EXPECT_TRUE(fk.error().code == ErrorCode::not_converged || fk.error().code == ErrorCode::singular)
      << fk.error().message;
}

}  // namespace
}  // namespace pkm

namespace pkm {
namespace {

// The benchmark path: a 40 mm circle in 0.1 mm steps while the three angles turn 0.001°, −0.0005°, 0.001° per
// step.
Pose path_pose(const Hexapod& h, int i) {
  PoseVector c = vector_from_pose(h.convention(), h.home());
  const double s = i * 0.1 / 40;
  c[0] += 40 * std::sin(s);
  c[1] += 40 * (1 - std::cos(s));
  for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(0.001) * i * (k == 4 ? -0.5 : 1.0);
  return pose_from_vector(h.convention(), c);
}

TEST(HexapodPathTracking, WorkspaceFormStaysOnThePathWithOneStepPerTick) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto& h = dynamic_cast<const Hexapod&>(*m.mechanism);
  PlatformFkWorkspace<6> workspace;
  Pose previous = path_pose(h, 0);
  long iterations = 0;
  double worst_mm = 0;
  constexpr int kSteps = 20000;
  for (int i = 1; i <= kSteps; ++i) {
    const Pose truth = path_pose(h, i);
    const auto fk = h.forward(*h.inverse(truth), previous, FkOptions{}, workspace);
    ASSERT_TRUE(fk.ok()) << "step " << i << ": " << fk.error().message;
    worst_mm = std::max(worst_mm, pose_distance(fk->pose, truth).position_mm);
    iterations += fk->iterations;
    previous = fk->pose;
  }
  EXPECT_LT(worst_mm, 1e-9);  // no drift of the extrapolated rotation over 20 000 ticks
  EXPECT_LT(static_cast<double>(iterations) / kSteps, 1.05);
  // The same solves without a workspace agree.
  const auto plain = h.forward(*h.inverse(path_pose(h, kSteps)), path_pose(h, kSteps - 1));
  ASSERT_TRUE(plain.ok());
  EXPECT_LT(pose_distance(plain->pose, previous).position_mm, 1e-9);
}

TEST(HexapodPathTracking, CrossingASingularityIsReportedAtTheCrossing) {
  // Along the same path det J changes sign between ticks 48194 and 48195 (the angles have grown to ~48°).
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto& h = dynamic_cast<const Hexapod&>(*m.mechanism);
  EXPECT_GT(h.twist_jacobian(path_pose(h, 48194)).determinant(), 0);
  EXPECT_LT(h.twist_jacobian(path_pose(h, 48195)).determinant(), 0);
  PlatformFkWorkspace<6> workspace;
  Pose previous = path_pose(h, 48100);
  for (int i = 48101; i <= 48194; ++i) {
    const auto fk = h.forward(*h.inverse(path_pose(h, i)), previous, FkOptions{}, workspace);
    ASSERT_TRUE(fk.ok()) << i;
    previous = fk->pose;
  }
  const auto across = h.forward(*h.inverse(path_pose(h, 48195)), previous, FkOptions{}, workspace);
  // Either the solver stays on the guess's side (a solution of those lengths in the guess's mode exists near
  // a singularity) or it reports the change of mode; it never returns the crossed pose as a same-mode
  // success.
  if (across.ok()) {
    EXPECT_GT(h.twist_jacobian(across->pose).determinant(), 0);
  } else {
    EXPECT_EQ(across.error().code, ErrorCode::wrong_branch);
  }
}

}  // namespace
}  // namespace pkm
