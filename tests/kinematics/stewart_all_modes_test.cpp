// Every assembly mode of the general 6-6 Gough–Stewart platform (kinematics/stewart_all_modes.hpp):
// the equations and their derivatives, the shipped start system, and the solver against the ground truth on
// random general and 3-fold symmetric layouts, Dietmaier's 40-real-solution instance, and a slow independent
// method (dense multi-start Newton).
#include "kinematics/stewart_all_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "core/wide_kernels.hpp"
#include "kinematics/stewart_lanes.hpp"
#include "machine/hexapod.hpp"
#include "machine/solution_set.hpp"

namespace pkm {
namespace {

using Joints = std::array<Eigen::Vector3d, 6>;

Complex random_complex_value(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const double re = normal(rng);
  return {re, normal(rng)};
}

StewartParameters random_complex_parameters(std::mt19937_64& rng) {
  std::array<Eigen::Vector3cd, 6> base, platform;
  std::array<Complex, 6> length_squared;
  for (int j = 0; j < 6; ++j) {
    for (int k = 0; k < 3; ++k) {
      base[j][k] = random_complex_value(rng);
      platform[j][k] = random_complex_value(rng);
    }
    length_squared[j] = random_complex_value(rng);
  }
  return StewartParameters::from_joints(base, platform, length_squared);
}

Pose random_pose(std::mt19937_64& rng, double tilt_rad, double height_mm) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Pose pose;
  const Eigen::Vector3d axis(u(rng), u(rng), u(rng));
  pose.rotation = Eigen::AngleAxisd(tilt_rad * u(rng), axis.normalized()).toRotationMatrix();
  pose.position_mm = Eigen::Vector3d(100 * u(rng), 100 * u(rng), height_mm + 100 * u(rng));
  return pose;
}

ActuatorVector lengths_at(const Joints& base, const Joints& platform, const Pose& pose) {
  ActuatorVector q(6);
  for (int j = 0; j < 6; ++j) q[j] = (pose.to_base(platform[j]) - base[j]).norm();
  return q;
}

bool holds_pose(const std::vector<FkSolution>& solutions, const Pose& pose) {
  return contains_solution(solutions, pose);
}

double worst_strut_residual_mm(const Joints& base, const Joints& platform, const ActuatorVector& q,
                               const std::vector<FkSolution>& solutions) {
  double worst = 0.0;
  for (const FkSolution& s : solutions) {
    const ActuatorVector at = lengths_at(base, platform, s.pose);
    worst = std::max(worst, (at - q).cwiseAbs().maxCoeff());
  }
  return worst;
}

// A general 6-6 layout: joints anywhere in a flat box (base about 1 m across, platform about half).
void random_general_layout(std::mt19937_64& rng, Joints& base, Joints& platform) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < 6; ++j) {
    base[j] = Eigen::Vector3d(500 * u(rng), 500 * u(rng), 100 * u(rng));
    platform[j] = Eigen::Vector3d(250 * u(rng), 250 * u(rng), 60 * u(rng));
  }
}

// A 3-fold symmetric machine layout: joint pairs 120° apart on a base and a platform circle, each pair split
// by a gap, the platform turned 60°, struts wired to the neighbouring pair (as most hexapods are built).
void symmetric_layout(double base_radius_mm, double base_gap_deg, double platform_radius_mm,
                      double platform_gap_deg, Joints& base, Joints& platform) {
  auto ring = [](double radius_mm, double half_gap_deg, double phase_deg, Joints& out) {
    for (int k = 0; k < 3; ++k) {
      for (int side = 0; side < 2; ++side) {
        const double angle = (phase_deg + 120.0 * k + (side ? half_gap_deg : -half_gap_deg)) * M_PI / 180.0;
        out[2 * k + side] = Eigen::Vector3d(radius_mm * std::cos(angle), radius_mm * std::sin(angle), 0.0);
      }
    }
  };
  Joints ring_platform;
  ring(base_radius_mm, base_gap_deg, 0.0, base);
  ring(platform_radius_mm, platform_gap_deg, 60.0, ring_platform);
  for (int j = 0; j < 6; ++j) platform[j] = ring_platform[(j + 5) % 6];
}

// The same real modes (poses to 1e-6 mm and 1e-9) and the same counts of finite and complex solutions.
void expect_same_modes(const StewartAllModes& a, const StewartAllModes& b, int trial) {
  ASSERT_EQ(a.real.size(), b.real.size()) << "trial " << trial;
  EXPECT_EQ(a.finite, b.finite) << "trial " << trial;
  EXPECT_EQ(a.complex, b.complex) << "trial " << trial;
  EXPECT_EQ(a.at_infinity, b.at_infinity) << "trial " << trial;
  EXPECT_EQ(a.failed, b.failed) << "trial " << trial;
  for (const StewartModeCandidate& mode : b.real) {
    const bool found = std::any_of(a.real.begin(), a.real.end(), [&](const StewartModeCandidate& m) {
      return (m.pose.position_mm - mode.pose.position_mm).norm() < 1e-6 &&
             (m.pose.rotation - mode.pose.rotation).norm() < 1e-9;
    });
    EXPECT_TRUE(found) << "trial " << trial;
  }
}

Hexapod hexapod_of(const Joints& base, const Joints& platform, const Pose& home) {
  HexapodGeometry geometry;
  geometry.base_joints_mm = base;
  geometry.platform_joints_mm = platform;
  return Hexapod(geometry, AngleConvention::abc, home);
}

// The slow independent method: Newton from many random poses (positions in a ball around the base, rotations
// uniform), every distinct converged pose kept.
std::vector<FkSolution> multi_start_modes(const Hexapod& hexapod, const ActuatorVector& q, int starts,
                                          std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double reach_mm = q.maxCoeff() * 1.5;
  FkOptions options;
  options.require_same_branch = false;
  std::vector<FkSolution> found;
  for (int s = 0; s < starts; ++s) {
    Pose guess;
    Eigen::Quaterniond rotation(normal(rng), normal(rng), normal(rng), normal(rng));
    guess.rotation = rotation.normalized().toRotationMatrix();
    guess.position_mm = Eigen::Vector3d(u(rng), u(rng), u(rng)) * reach_mm;
    auto solution = hexapod.forward(q, guess, options);
    if (solution && solution->residual_mm < 1e-9 && !contains_solution(found, solution->pose)) {
      found.push_back(*solution);
    }
  }
  return found;
}

// make sanitize sets PKM_RANDOM_GEOMETRIES (its runs are ~20× slower): the random suites shrink there.
bool reduced_run() {
  return std::getenv("PKM_RANDOM_GEOMETRIES") != nullptr;
}

TEST(StewartSystem, LinearisationMatchesCentralDifferencesOfTheEquations) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Vector4cd chart;
    for (int i = 0; i < 4; ++i) chart[i] = random_complex_value(rng);
    const StewartSystem system(chart);
    const StewartParameters p = random_complex_parameters(rng);
    const StewartParameters rate = random_complex_parameters(rng).minus(p);
    StudyPoint x;
    for (int i = 0; i < 8; ++i) x[i] = random_complex_value(rng);
    StudyJacobian jx;
    StudyPoint f, ft, plus, minus;
    system.linearise(p, &rate, x, &f, jx, &ft);
    StudyPoint f_only;
    system.evaluate(p, x, f_only);
    EXPECT_LT((f - f_only).norm(), 1e-12 * (1 + f.norm()));
    const double h = 1e-6;
    for (int i = 0; i < 8; ++i) {
      for (const Complex step : {Complex(h, 0), Complex(0, h)}) {
        StudyPoint a = x, b = x;
        a[i] += step;
        b[i] -= step;
        system.evaluate(p, a, plus);
        system.evaluate(p, b, minus);
        // Holomorphic: the same derivative along the real and the imaginary direction.
        const StudyPoint numeric = (plus - minus) / (2.0 * step);
        EXPECT_LT((numeric - jx.col(i)).norm(), 1e-6 * (1 + jx.col(i).norm())) << "column " << i;
      }
    }
    system.evaluate(p.lerp_rate(rate, h), x, plus);
    system.evaluate(p.lerp_rate(rate, -h), x, minus);
    EXPECT_LT(((plus - minus) / (2 * h) - ft).norm(), 1e-6 * (1 + ft.norm()));
  }
}

TEST(StewartSystem, TheTaylorCoefficientsOfAPathPredictItToTheirOrder) {
  // The predictor's coefficients (path_taylor): the Taylor polynomial of order K, against the path itself
  // (Newton at t = h from the prediction), must be off by O(h^(K+1)): halving h divides the error by 2^(K+1).
  const StewartStartSystem& start = stewart_start_system();
  const StewartSystem system(start.chart);
  std::mt19937_64 rng(43);
  const StewartParameters rate = random_complex_parameters(rng).minus(start.parameters);
  for (int root = 0; root < 3; ++root) {
    StudyJacobian jx;
    ComplexLu<8> lu;
    system.linearise(start.parameters, nullptr, start.roots[root], nullptr, jx, nullptr);
    ASSERT_TRUE(lu.compute(jx));
    std::array<StudyPoint, 5> taylor;
    taylor[0] = start.roots[root];
    system.path_taylor(start.parameters, rate, lu, 4, taylor.data());
    for (int order = 1; order <= 4; ++order) {
      std::array<double, 2> error;
      for (int i = 0; i < 2; ++i) {
        const double h = 0.01 / (1 << i);
        StudyPoint predicted = taylor[order];
        for (int k = order - 1; k >= 0; --k) predicted = taylor[k] + h * predicted;
        StudyPoint x = predicted;
        double pivot_ratio = 0.0;
        refine_stewart_point(system, start.parameters.lerp_rate(rate, h), x, 10, 1e-15, pivot_ratio);
        error[i] = (x - predicted).norm();
      }
      EXPECT_GT(error[0] / error[1], 0.7 * (2 << order)) << "root " << root << ", order " << order;
    }
  }
}

TEST(StewartLanes, TheTrackersPairedArithmeticEqualsTheReference) {
  // The tracker's two-lane kernels (stewart_lanes.hpp) against StewartSystem and ComplexLu<8>: equations,
  // Jacobian, a solve, and the Taylor coefficients to order 5, near every start solution.
  std::mt19937_64 rng(5);
  const StewartStartSystem& start = stewart_start_system();
  const StewartSystem system(start.chart);
  const StewartParameters target = random_complex_parameters(rng);
  const StewartParameters rate = target.minus(start.parameters);
  const stewart_lanes::Legs legs = stewart_lanes::Legs::of(start.parameters);
  const stewart_lanes::Legs legs_rate = stewart_lanes::Legs::of(rate);
  for (std::size_t r = 0; r < start.roots.size(); ++r) {
    StudyPoint x = start.roots[r];
    for (int i = 0; i < 8; ++i) x[i] += 0.01 * random_complex_value(rng);
    StudyPoint f;
    StudyJacobian jx;
    system.linearise(start.parameters, nullptr, x, &f, jx, nullptr);
    stewart_lanes::Vec8 lane_f;
    stewart_lanes::Mat8 lane_jx;
    stewart_lanes::linearise(legs, start.chart, stewart_lanes::Vec8::of(x), &lane_f, lane_jx);
    // Near a root f is a small difference of terms of the size |J|·|x| (the equations are quadratic), which
    // the two sum in different orders: their rounding is relative to that size, not to |f|.
    EXPECT_LT((lane_f.point() - f).norm(), 1e-14 * (f.norm() + jx.norm() * x.norm())) << "root " << r;
    for (int c = 0; c < 8; ++c) {
      for (int i = 0; i < 8; ++i) {
        const Complex entry(lane_jx.column[c][i / 2].re[i % 2], lane_jx.column[c][i / 2].im[i % 2]);
        EXPECT_LT(std::abs(entry - jx(i, c)), 1e-14 * jx.norm())
            << "root " << r << ", (" << i << ", " << c << ")";
      }
    }
    ComplexLu<8> lu;
    ASSERT_TRUE(lu.compute(jx));
    stewart_lanes::LaneLu lane_lu;
    ASSERT_TRUE(lane_lu.compute(lane_jx));
    // The lanes pivot by columns: the same pivots as the reference's row pivoting on the transpose.
    ComplexLu<8> transposed_lu;
    ASSERT_TRUE(transposed_lu.compute(jx.transpose()));
    EXPECT_NEAR(lane_lu.pivot_ratio(), transposed_lu.pivot_ratio(), 1e-12);
    const StudyPoint solved = lu.solve(f);
    EXPECT_LT((lane_lu.solve(stewart_lanes::Vec8::of(f)).point() - solved).norm(), 1e-12 * solved.norm());

    std::array<StudyPoint, 6> taylor;
    taylor[0] = start.roots[r];
    system.linearise(start.parameters, nullptr, taylor[0], nullptr, jx, nullptr);
    ASSERT_TRUE(lu.compute(jx));
    system.path_taylor(start.parameters, rate, lu, 5, taylor.data());
    std::array<stewart_lanes::Vec8, 6> lane_taylor;
    lane_taylor[0] = stewart_lanes::Vec8::of(taylor[0]);
    stewart_lanes::linearise(legs, start.chart, lane_taylor[0], nullptr, lane_jx);
    ASSERT_TRUE(lane_lu.compute(lane_jx));
    stewart_lanes::path_taylor<5>(legs, legs_rate, lane_lu, lane_taylor.data());
    for (int k = 1; k <= 5; ++k) {
      EXPECT_LT((lane_taylor[k].point() - taylor[k]).norm(), 1e-11 * taylor[k].norm())
          << "root " << r << ", order " << k;
    }
  }
}

// Writes m through `columns` (column c of m at columns.column[c]), as the tracker's linearise does.
void write_lanes(const StudyJacobian& m, const stewart_lanes::Columns& columns) {
  for (int c = 0; c < 8; ++c) {
    for (int i = 0; i < 8; ++i) {
      columns.column[c][i / 2].re[i % 2] = m(i, c).real();
      columns.column[c][i / 2].im[i % 2] = m(i, c).imag();
    }
  }
}

stewart_lanes::Mat8 lanes_of(const StudyJacobian& m) {
  stewart_lanes::Mat8 lanes;
  stewart_lanes::Columns columns;
  for (int c = 0; c < 8; ++c) columns.column[c] = lanes.column[c];
  write_lanes(m, columns);
  return lanes;
}

TEST(StewartLanes, AFactorisationInTheLastColumnOrderSolvesOrRefuses) {
  // The tracker factorises most Jacobians in the column order of the one before, without a pivot search
  // (LaneLu::factorise_in_last_order). On random matrices: a small change keeps the order and solves as a
  // pivoted LU does; a change that makes the old pivot small against its row is refused, and the pivoted
  // factorisation then takes over.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> column(0, 7);
  for (int trial = 0; trial < 50; ++trial) {
    StudyJacobian a, change;
    StudyPoint b;
    for (int i = 0; i < 8; ++i) {
      b[i] = random_complex_value(rng);
      for (int c = 0; c < 8; ++c) {
        a(i, c) = random_complex_value(rng);
        change(i, c) = random_complex_value(rng);
      }
    }
    stewart_lanes::LaneLu lu;
    write_lanes(a, lu.columns_in_last_order());  // before any factorisation: the matrix's own order
    ASSERT_TRUE(lu.factorise());
    const StudyJacobian nearby = a + 1e-3 * change;
    write_lanes(nearby, lu.columns_in_last_order());
    ASSERT_TRUE(lu.factorise_in_last_order()) << "trial " << trial;
    const StudyPoint expected = nearby.fullPivLu().solve(b);
    EXPECT_LT((lu.solve(stewart_lanes::Vec8::of(b)).point() - expected).norm(), 1e-12 * expected.norm())
        << "trial " << trial;

    // Row 0 small but in one column, which the pivoted factorisation puts first; then small in that column
    // but in another: the old first pivot is a thousandth of its row's largest entry.
    StudyJacobian first = a, second = a;
    const int chosen = column(rng), other = (chosen + 1 + column(rng) % 7) % 8;
    for (int c = 0; c < 8; ++c) {
      first(0, c) = 1e-3 * a(0, c);
      second(0, c) = 1e-3 * a(0, c);
    }
    first(0, chosen) = a(0, chosen) / std::abs(a(0, chosen));
    second(0, other) = a(0, other) / std::abs(a(0, other));
    ASSERT_TRUE(lu.compute(lanes_of(first)));
    write_lanes(second, lu.columns_in_last_order());
    EXPECT_FALSE(lu.factorise_in_last_order()) << "trial " << trial;
    ASSERT_TRUE(lu.compute(lanes_of(second)));
    const StudyPoint solved = second.fullPivLu().solve(b);
    EXPECT_LT((lu.solve(stewart_lanes::Vec8::of(b)).point() - solved).norm(), 1e-12 * solved.norm())
        << "trial " << trial;
  }
}

TEST(StewartSystem, ARealPoseSolvesItsOwnEquationsAndComesBack) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    Joints base, platform;
    random_general_layout(rng, base, platform);
    const Pose pose = random_pose(rng, 0.8, 500.0);
    // The chart of the real pose's own e, so that x is on it.
    const StudyPoint x = study_point_of(pose);
    Eigen::Vector4cd chart = Eigen::Vector4cd::Zero();
    chart[0] = 1.0 / x[0];
    std::array<Eigen::Vector3cd, 6> base_c, platform_c;
    std::array<Complex, 6> length_squared;
    for (int j = 0; j < 6; ++j) {
      base_c[j] = base[j].cast<Complex>();
      platform_c[j] = platform[j].cast<Complex>();
      length_squared[j] = (pose.to_base(platform[j]) - base[j]).squaredNorm();
    }
    StudyPoint f;
    StewartSystem(chart).evaluate(StewartParameters::from_joints(base_c, platform_c, length_squared), x, f);
    EXPECT_LT(f.norm(), 1e-9 * 1e6);  // squared lengths of ~1e6 mm²
  }
}

TEST(StewartStart, TheShippedFortySolutionsSolveTheStartInstanceAndAreDistinctAndRegular) {
  const StewartStartSystem& start = stewart_start_system();
  ASSERT_EQ(start.roots.size(), 40u);
  const StewartSystem system(start.chart);
  for (std::size_t a = 0; a < start.roots.size(); ++a) {
    StudyPoint f;
    system.evaluate(start.parameters, start.roots[a], f);
    EXPECT_LT(f.norm(), 1e-10) << "solution " << a;
    StudyPoint x = start.roots[a];
    double pivot_ratio = 0.0;
    refine_stewart_point(system, start.parameters, x, 2, 1e-15, pivot_ratio);
    EXPECT_GT(pivot_ratio, 1e-6) << "solution " << a << " is (nearly) singular";
    for (std::size_t b = a + 1; b < start.roots.size(); ++b) {
      EXPECT_GT((start.roots[a] - start.roots[b]).norm(), 1e-4) << a << " and " << b;
    }
  }
}

TEST(StewartStart, MonodromyFromAnotherSeedFindsFortySolutionsAndNoMore) {
  // Forty is the generic root count (Raghavan; Ronga–Vust; Lazard; Mourrain): monodromy from one known
  // solution must reach exactly as many, and running it longer finds nothing new.
  const StewartStartSystem start = stewart_start_by_monodromy(77, 40, 40, 4);
  EXPECT_EQ(start.roots.size(), 40u);
}

TEST(StewartAllModes, DietmaiersInstanceHasFortyRealAssemblyModes) {
  // P. Dietmaier (1998), "The Stewart-Gough platform of general geometry can have 40 real postures"; the
  // instance as tabulated with six decimals (unit length: here 100 mm).
  const double unit_mm = 100.0;
  const std::array<std::array<double, 3>, 6> base_data = {{{0, 0, 0},
                                                           {1.107915, 0, 0},
                                                           {0.549094, 0.756063, 0},
                                                           {0.735077, -0.223935, 0.525991},
                                                           {0.514188, -0.526063, -0.368418},
                                                           {0.590473, 0.094733, -0.205018}}};
  const std::array<std::array<double, 3>, 6> platform_data = {{{0, 0, 0},
                                                               {0.542805, 0, 0},
                                                               {0.956919, -0.528915, 0},
                                                               {0.665885, -0.353482, 1.402538},
                                                               {0.478359, 1.158742, 0.107672},
                                                               {-0.137087, -0.235121, 0.353913}}};
  const std::array<double, 6> lengths = {1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071};
  Joints base, platform;
  ActuatorVector q(6);
  for (int j = 0; j < 6; ++j) {
    base[j] = Eigen::Vector3d(base_data[j][0], base_data[j][1], base_data[j][2]) * unit_mm;
    platform[j] = Eigen::Vector3d(platform_data[j][0], platform_data[j][1], platform_data[j][2]) * unit_mm;
    q[j] = lengths[j] * unit_mm;
  }
  // Home: any pose; the modes do not depend on it.
  const Hexapod hexapod = hexapod_of(base, platform, Pose{});
  auto modes = hexapod.assembly_modes(q);
  ASSERT_TRUE(modes) << modes.error().message;
  EXPECT_EQ(modes->solutions.size(), 40u);
  EXPECT_EQ(modes->report.complex, 0);
  EXPECT_EQ(modes->report.at_infinity, 0);
  EXPECT_EQ(modes->report.failed, 0);
  EXPECT_LE(worst_strut_residual_mm(base, platform, q, modes->solutions), 1e-10);
}

TEST(StewartAllModes, RandomGeneralGeometriesFindTheGroundTruthAndAnEvenNumberOfModes) {
  // The goal: the ground truth among the real solutions on ≥ 99.9 % of 2000 random geometries (fkSGP:
  // 1993/2000).
  const int count = reduced_run() ? 20 : 2000;
  std::mt19937_64 rng(2026);
  int found = 0, failed_paths = 0;
  for (int trial = 0; trial < count; ++trial) {
    Joints base, platform;
    random_general_layout(rng, base, platform);
    const Pose truth = random_pose(rng, 1.0, 500.0);
    const ActuatorVector q = lengths_at(base, platform, truth);
    const Hexapod hexapod = hexapod_of(base, platform, truth);
    auto modes = hexapod.assembly_modes(q);
    ASSERT_TRUE(modes) << "trial " << trial << ": " << modes.error().message;
    if (holds_pose(modes->solutions, truth)) ++found;
    const int real = static_cast<int>(modes->solutions.size());
    EXPECT_EQ(real % 2, 0) << "trial " << trial;
    EXPECT_LE(real, 40);
    EXPECT_EQ(real + modes->report.complex + modes->report.at_infinity + modes->report.failed, 40)
        << "trial " << trial;
    EXPECT_LE(worst_strut_residual_mm(base, platform, q, modes->solutions), 1e-10) << "trial " << trial;
    failed_paths += modes->report.failed;
  }
  EXPECT_GE(found, count - count / 1000) << found << " of " << count;
  EXPECT_LE(failed_paths, count / 100);
  RecordProperty("ground_truth_found", found);
  std::printf("ground truth found in %d of %d; %d failed paths\n", found, count, failed_paths);
}

TEST(StewartAllModes, StoppingOnceEverySolutionIsKnownLosesNothing) {
  // The paths left unfollowed once the endpoints and their conjugates number 40 change no real mode and no
  // count: the same instances with every path followed give the same real poses.
  std::mt19937_64 rng(77);
  int skipped = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Joints base, platform;
    random_general_layout(rng, base, platform);
    const Pose truth = random_pose(rng, 1.0, 500.0);
    const ActuatorVector q = lengths_at(base, platform, truth);
    std::array<double, 6> lengths;
    for (int j = 0; j < 6; ++j) lengths[j] = q[j];
    StewartAllModesOptions every_path;
    every_path.stop_when_all_known = false;
    const StewartAllModes stopped = stewart_all_modes(base, platform, lengths);
    const StewartAllModes full = stewart_all_modes(base, platform, lengths, every_path);
    EXPECT_EQ(full.skipped, 0);
    skipped += stopped.skipped;
    expect_same_modes(stopped, full, trial);
  }
  // The saving is real: on general geometries some paths are left out.
  EXPECT_GT(skipped, 60);
  std::printf("%d of %d paths not followed\n", skipped, 60 * 40);
}

TEST(StewartAllModes, TheWideKernelsFindWhatTheBaselineFinds) {
  // The tracker's AVX2/FMA build (chosen at run time where the processor has it) against its baseline build:
  // the same modes on general and 3-fold symmetric layouts. Fused multiply–adds round differently, so the
  // steps may differ in the last digits; the solutions may not.
  std::mt19937_64 rng(515);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  long steps_wide = 0, steps_baseline = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Joints base, platform;
    if (trial % 2 == 0) {
      random_general_layout(rng, base, platform);
    } else {
      symmetric_layout(500.0 + 100.0 * u(rng), 10.0 + 5.0 * u(rng), 250.0 + 50.0 * u(rng),
                       12.0 + 5.0 * u(rng), base, platform);
    }
    const ActuatorVector q = lengths_at(base, platform, random_pose(rng, 0.5, 500.0));
    std::array<double, 6> lengths;
    for (int j = 0; j < 6; ++j) lengths[j] = q[j];
    StewartAllModesOptions baseline;
    baseline.tracking.wide_kernels = false;
    const StewartAllModes wide = stewart_all_modes(base, platform, lengths);
    const StewartAllModes plain = stewart_all_modes(base, platform, lengths, baseline);
    expect_same_modes(wide, plain, trial);
    steps_wide += wide.steps;
    steps_baseline += plain.steps;
  }
  std::printf("AVX2/FMA kernels %s; steps %ld (baseline %ld)\n",
              wide_kernels_available() ? "in use" : "not available on this processor", steps_wide,
              steps_baseline);
}

TEST(StewartAllModes, SeveralThreadsFindWhatOneThreadFinds) {
  // The paths handed out to several threads: the same modes and counts as one thread, whichever path ends
  // first, and never fewer paths followed than one thread follows (those in flight when the last solution
  // turns up are finished).
  std::mt19937_64 rng(616);
  for (int trial = 0; trial < 30; ++trial) {
    Joints base, platform;
    random_general_layout(rng, base, platform);
    const ActuatorVector q = lengths_at(base, platform, random_pose(rng, 0.5, 500.0));
    std::array<double, 6> lengths;
    for (int j = 0; j < 6; ++j) lengths[j] = q[j];
    StewartAllModesOptions threaded;
    threaded.threads = 3 + trial % 3;
    const StewartAllModes one = stewart_all_modes(base, platform, lengths);
    const StewartAllModes several = stewart_all_modes(base, platform, lengths, threaded);
    expect_same_modes(one, several, trial);
    EXPECT_LE(several.skipped, one.skipped) << "trial " << trial;
  }
}

TEST(StewartAllModes, RealModeCountsEqualADenseMultiStartSearchOnASubset) {
  // The slow independent method can only miss solutions: every mode it finds must be among the homotopy's,
  // and with enough starts the counts agree.
  const int count = reduced_run() ? 2 : 12;
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < count; ++trial) {
    Joints base, platform;
    if (trial % 2 == 0) {
      random_general_layout(rng, base, platform);
    } else {
      std::uniform_real_distribution<double> u(0.0, 1.0);
      symmetric_layout(300 + 300 * u(rng), 3 + 10 * u(rng), 100 + 100 * u(rng), 3 + 10 * u(rng), base,
                       platform);
    }
    const Pose truth = random_pose(rng, 0.5, 400.0);
    const ActuatorVector q = lengths_at(base, platform, truth);
    const Hexapod hexapod = hexapod_of(base, platform, truth);
    auto modes = hexapod.assembly_modes(q);
    ASSERT_TRUE(modes) << modes.error().message;
    const std::vector<FkSolution> slow = multi_start_modes(hexapod, q, reduced_run() ? 300 : 4000, rng);
    for (const FkSolution& s : slow) {
      EXPECT_TRUE(holds_pose(modes->solutions, s.pose))
          << "trial " << trial << ": the multi-start search found "
          << "a mode the homotopy missed";
    }
    if (!reduced_run()) {
      EXPECT_EQ(slow.size(), modes->solutions.size()) << "trial " << trial;
    }
  }
}

TEST(StewartAllModes, SymmetricMachineLayoutsFindTheGroundTruthEveryTime) {
  // fkSGP returns nothing on these (0/200 measured): its elimination template assumes a generic geometry.
  const int count = reduced_run() ? 10 : 200;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < count; ++trial) {
    Joints base, platform;
    symmetric_layout(200 + 400 * u(rng), 1 + 12 * u(rng), 60 + 140 * u(rng), 1 + 12 * u(rng), base, platform);
    const Pose truth = random_pose(rng, 0.5, 450.0);
    const ActuatorVector q = lengths_at(base, platform, truth);
    const Hexapod hexapod = hexapod_of(base, platform, truth);
    auto modes = hexapod.assembly_modes(q);
    ASSERT_TRUE(modes) << "trial " << trial << ": " << modes.error().message;
    EXPECT_TRUE(holds_pose(modes->solutions, truth)) << "trial " << trial;
    EXPECT_EQ(modes->solutions.size() % 2, 0u) << "trial " << trial;
    EXPECT_EQ(modes->report.failed, 0) << "trial " << trial;
    EXPECT_LE(worst_strut_residual_mm(base, platform, q, modes->solutions), 1e-10) << "trial " << trial;
  }
}

TEST(StewartAllModes, TheHomotopyAgreesWithTheOneDimensionalScanOnMergedJointLayouts) {
  // Two independent methods on the 6-3 layouts where both apply: the 1-D scan and the homotopy called
  // directly. Hexapod returns their union; the homotopy alone must already hold all of it.
  std::mt19937_64 rng(5);
  Joints base, platform;
  symmetric_layout(400.0, 15.0, 200.0, 0.0, base, platform);  // gap 0: platform joints merged in pairs
  for (int trial = 0; trial < (reduced_run() ? 2 : 20); ++trial) {
    const Pose truth = random_pose(rng, 0.4, 450.0);
    const ActuatorVector q = lengths_at(base, platform, truth);
    const Hexapod hexapod = hexapod_of(base, platform, truth);
    auto scan = hexapod.assembly_modes(q);  // the union of the scan and the homotopy
    ASSERT_TRUE(scan) << scan.error().message;
    EXPECT_NE(scan->report.method.find("scan"), std::string::npos);
    std::array<double, 6> lengths_mm;
    for (int j = 0; j < 6; ++j) lengths_mm[j] = q[j];
    const StewartAllModes homotopy = stewart_all_modes(base, platform, lengths_mm);
    std::vector<FkSolution> homotopy_modes;
    for (const StewartModeCandidate& c : homotopy.real) {
      auto polished = hexapod.forward(q, c.pose, FkOptions{.require_same_branch = false});
      if (polished && !contains_solution(homotopy_modes, polished->pose)) homotopy_modes.push_back(*polished);
    }
    for (const FkSolution& s : scan->solutions) {
      EXPECT_TRUE(holds_pose(homotopy_modes, s.pose)) << "trial " << trial;
    }
    // The homotopy may find more: the scan misses a pair of roots closer than one sample (Hexapod keeps the
    // union of both; assembly_modes above is that union).
    EXPECT_EQ(homotopy_modes.size(), scan->solutions.size()) << "trial " << trial;
  }
}

TEST(StewartAllModes, AnArchitecturallySingularLayoutIsReportedNotLoopedOn) {
  // Similar planar base and platform hexagons with their joints on a conic (here circles, the platform a
  // scaled copy of the base): the Jacobian is singular at every pose (Ma–Angeles' architecture singularity),
  // so any strut lengths that fit give a continuum of poses. The solver must come back and say so.
  Joints base, platform;
  const std::array<double, 6> angles_deg = {0, 50, 120, 170, 240, 290};
  for (int j = 0; j < 6; ++j) {
    const double a = angles_deg[j] * M_PI / 180.0;
    base[j] = Eigen::Vector3d(400 * std::cos(a), 400 * std::sin(a), 0);
    platform[j] = Eigen::Vector3d(200 * std::cos(a), 200 * std::sin(a), 0);
  }
  Pose pose;
  pose.position_mm = Eigen::Vector3d(20, -10, 400);
  pose.rotation = Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const ActuatorVector q = lengths_at(base, platform, pose);
  const Hexapod hexapod = hexapod_of(base, platform, pose);
  EXPECT_LT(std::abs(hexapod.twist_jacobian(pose).determinant()), 1e-9 * std::pow(400.0, 3));
  auto modes = hexapod.assembly_modes(q);
  ASSERT_FALSE(modes) << "a continuum reported as " << modes->solutions.size() << " isolated modes";
  EXPECT_EQ(modes.error().code, ErrorCode::singular) << modes.error().message;
  EXPECT_NE(modes.error().message.find("architecturally singular"), std::string::npos)
      << modes.error().message;
  // Moving one platform joint off the conic breaks the architecture singularity: modes are listed again.
  platform[0].z() += 30.0;
  const Hexapod broken = hexapod_of(base, platform, pose);
  auto listed = broken.assembly_modes(lengths_at(base, platform, pose));
  ASSERT_TRUE(listed) << listed.error().message;
  EXPECT_TRUE(holds_pose(listed->solutions, pose));
}

TEST(StewartAllModes, BadLengthsAreRefusedWithAMessage) {
  Joints base, platform;
  symmetric_layout(400.0, 10.0, 200.0, 10.0, base, platform);
  std::mt19937_64 rng(1);
  const Hexapod hexapod = hexapod_of(base, platform, random_pose(rng, 0.1, 400));
  ActuatorVector q = ActuatorVector::Constant(6, 450.0);
  q[2] = std::nan("");
  auto nan = hexapod.assembly_modes(q);
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.error().code, ErrorCode::bad_input);
  EXPECT_NE(nan.error().message.find("strut 3"), std::string::npos) << nan.error().message;
  q[2] = -5.0;
  EXPECT_FALSE(hexapod.assembly_modes(q));
  EXPECT_FALSE(hexapod.assembly_modes(ActuatorVector::Constant(5, 450.0)));
}

TEST(StewartAllModes, LengthsNoPoseFitsAreReportedUnreachable) {
  Joints base, platform;
  symmetric_layout(400.0, 10.0, 200.0, 10.0, base, platform);
  const Hexapod hexapod = hexapod_of(base, platform, Pose{});
  // One strut far longer than the others can reach with a rigid platform.
  ActuatorVector q = ActuatorVector::Constant(6, 450.0);
  q[0] = 5000.0;
  auto modes = hexapod.assembly_modes(q);
  ASSERT_FALSE(modes);
  EXPECT_EQ(modes.error().code, ErrorCode::unreachable);
}

}  // namespace
}  // namespace pkm
