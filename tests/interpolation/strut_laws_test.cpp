// Analytic strut laws along planned paths (Smirnov 2019, §5.2.2, eqs. 147–150): the model each kind of
// segment gets, its fit error against inverse kinematics solved here (independently of the laws), and the
// behaviour at the path's ends and on other mechanisms.
#include "interpolation/methods/strut_laws.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <numbers>
#include <random>

#include "path/curve.hpp"
#include "planning/plan_test_support.hpp"
#include "program/part_program.hpp"
#include "source_paths.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using interpolation::LawFitSettings;
using interpolation::LawModel;
using interpolation::StrutLaws;

Machine ch5_hexapod() {
  return test::machine_from_example("examples/machines/hexapod_ch5.yaml");
}

program::CanonicalProgram example_program(const Machine& machine, const std::string& name) {
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions options;
  options.start_mm = start.start_mm;
  options.start_abc_deg = start.start_abc_deg;
  auto program = program::load_part_program(test::source_path("examples/programs/" + name), options);
  if (!program) {
    ADD_FAILURE() << program.error().message;
    throw std::runtime_error(program.error().message);
  }
  return std::move(program.value());
}

StrutLaws fit_or_fail(const Machine& machine, const path::Path& path, const LawFitSettings& settings = {}) {
  auto laws = StrutLaws::fit(machine, path, settings, "test.ngc");
  if (!laws) {
    ADD_FAILURE() << laws.error().message;
    throw std::runtime_error(laws.error().message);
  }
  return std::move(laws.value());
}

/// Inverse kinematics at s, straight from the path and the mechanism.
ActuatorVector ik_at(const Machine& machine, const path::Path& path, double s) {
  int segment = 0;
  const path::PathPoint point = path.evaluate(s, segment);
  auto ik = machine.mechanism->inverse(Pose{point.position_mm, point.rotation.toRotationMatrix()});
  if (!ik) {
    ADD_FAILURE() << ik.error().message;
    throw std::runtime_error(ik.error().message);
  }
  return *ik;
}

/// Largest |law − IK| at s0 and at `count` points spread evenly inside [s0, s1) (s1 itself belongs to the
/// next piece).
double law_deviation(const Machine& machine, const path::Path& path, const StrutLaws& laws, double s0,
                     double s1, int count) {
  double worst = 0.0;
  int hint = 0;
  std::array<double, kMaxActuators> q{};
  for (int k = 0; k < count; ++k) {
    const double s = s0 + (s1 - s0) * (k == 0 ? 0.0 : (k - 0.5) / (count - 1));
    EXPECT_TRUE(laws.evaluate(s, hint, q.data()));
    const ActuatorVector exact = ik_at(machine, path, s);
    for (int j = 0; j < laws.actuator_count(); ++j) worst = std::max(worst, std::abs(q[j] - exact[j]));
  }
  return worst;
}

/// Pieces of the laws on path segments for which `take(segment)` holds.
template <class Take>
std::vector<int> pieces_where(const StrutLaws& laws, const path::Path& path, Take take) {
  std::vector<int> pieces;
  for (int p = 0; p < laws.piece_count(); ++p) {
    if (take(path.segments[laws.piece(p).segment])) pieces.push_back(p);
  }
  return pieces;
}

/// Least-squares polynomial of `degree` in L itself, on `nodes` Chebyshev nodes of [s0, s1]; its largest
/// error over 201 even points: the "fit L directly" alternative that §5.2.2 rejects.
double plain_polynomial_error(const Machine& machine, const path::Path& path, double s0, double s1,
                              int degree, int nodes) {
  const int actuators = machine.mechanism->actuator_count();
  auto s_of = [&](double u) { return 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * u; };
  Eigen::MatrixXd basis(nodes, degree + 1);
  Eigen::MatrixXd values(nodes, actuators);
  for (int i = 0; i < nodes; ++i) {
    const double u = std::cos((2.0 * i + 1.0) * std::numbers::pi / (2.0 * nodes));
    for (int k = 0; k <= degree; ++k) basis(i, k) = std::pow(u, k);
    const ActuatorVector q = ik_at(machine, path, s_of(u));
    for (int j = 0; j < actuators; ++j) values(i, j) = q[j];
  }
  const Eigen::MatrixXd c = basis.colPivHouseholderQr().solve(values);
  double worst = 0.0;
  for (int k = 0; k <= 200; ++k) {
    const double u = -1.0 + 2.0 * k / 200.0;
    const ActuatorVector q = ik_at(machine, path, s_of(u));
    for (int j = 0; j < actuators; ++j) {
      double fitted = 0.0;
      for (int m = degree; m >= 0; --m) fitted = fitted * u + c(m, j);
      worst = std::max(worst, std::abs(fitted - q[j]));
    }
  }
  return worst;
}

// Lines (§5.2.2): along a straight line at constant orientation L² is exactly quadratic, so eq. 149 fits it
// to round-off, while a quadratic (or cubic) in L itself leaves a "significant" error.
TEST(StrutLawLine, Ch5LineIsSqrtQuadraticToRoundOffAndAPlainQuadraticIsNot) {
  const Machine machine = ch5_hexapod();
  const auto plan = test::plan_or_fail(machine, example_program(machine, "ch5_line.ngc"));
  const path::Path& path = plan.path;
  const StrutLaws laws = fit_or_fail(machine, path);
  const auto& report = laws.report();
  ASSERT_GE(report.pieces, 2);  // the G0 to the start and the test line
  EXPECT_EQ(report.sqrt_quadratic, report.pieces);
  EXPECT_EQ(report.pieces, static_cast<int>(path.segments.size())) << "lines need no split";
  EXPECT_LT(report.max_fit_error, 1e-9);
  for (int p = 0; p < laws.piece_count(); ++p) EXPECT_EQ(laws.model(p), LawModel::sqrt_quadratic) << p;
  EXPECT_LT(law_deviation(machine, path, laws, 0.0, path.length(), 997), 1e-9);

  // The test line (−50, 0, 700) → (50, 0, 700): the last segment.
  const path::Segment& line = path.segments.back();
  ASSERT_NEAR(line.length, 100.0, 1e-9);
  const double s0 = line.s_start, s1 = line.s_start + line.length;
  const double sqrt_error = law_deviation(machine, path, laws, s0, s1, 201);
  const double quadratic_error = plain_polynomial_error(machine, path, s0, s1, 2, 8);
  const double cubic_error = plain_polynomial_error(machine, path, s0, s1, 3, 8);
  RecordProperty("sqrt_quadratic_error_mm", fmt::format("{:.3g}", sqrt_error));
  RecordProperty("plain_quadratic_error_mm", fmt::format("{:.3g}", quadratic_error));
  RecordProperty("plain_cubic_error_mm", fmt::format("{:.3g}", cubic_error));
  EXPECT_GE(quadratic_error, 100.0 * std::max(sqrt_error, LawFitSettings{}.tolerance));
  EXPECT_GT(cubic_error, LawFitSettings{}.tolerance) << "even a cubic in L misses the tolerance";
}

// Arcs (§5.2.2, Fig. 166): a flat arc at constant orientation has L² = a0 + a1 cos θ + b1 sin θ: eqs. 148/150
// fit it to round-off, in the XY plane (G17) and in another plane (G18), level and tilted.
TEST(StrutLawArc, FlatArcsAreSqrtFourierToRoundOff) {
  const Machine machine = ch5_hexapod();
  const auto program = test::gcode_for(machine,
                                       "G21 G90 G17\n"
                                       "G0 X-70 Y0 Z-100\n"
                                       "G3 X0 Y-70 I70 J0 F1000\n"  // line 3: quarter circle, R = 70
                                       "G0 X-20 Y10 Z-20 A4 B-3\n"
                                       "G2 X-20 Y-30 I0 J-20\n"    // line 5: half circle, tilted platform
                                       "G18 G2 X20 Z-20 I20 K0\n"  // line 6: XZ plane
                                       "M2\n",
                                       "arcs.ngc");
  const auto plan = test::plan_or_fail(machine, program);
  const path::Path& path = plan.path;
  const StrutLaws laws = fit_or_fail(machine, path);
  const auto arcs = pieces_where(laws, path, [&](const path::Segment& seg) {
    return !seg.is_blend() && path.curves[seg.curve_a].kind == path::CurveKind::helix;
  });
  ASSERT_GE(arcs.size(), 3u);
  std::array<bool, 7> seen{};
  for (int p : arcs) {
    EXPECT_EQ(laws.model(p), LawModel::sqrt_fourier) << "line " << laws.line(p);
    EXPECT_LT(laws.piece(p).fit_error, 1e-9) << "line " << laws.line(p);
    EXPECT_LT(law_deviation(machine, path, laws, laws.piece(p).s_start, laws.piece(p).s_end, 301), 1e-9)
        << "line " << laws.line(p);
    seen[laws.line(p)] = true;
  }
  EXPECT_TRUE(seen[3] && seen[5] && seen[6]);
  EXPECT_EQ(laws.report().sqrt_fourier, static_cast<int>(arcs.size()));
}

// General paths (§5.2.2) and the fall-backs: a helix, a move that turns the platform, a rotation-only move
// and corner blends get degree-6 polynomials within the tolerance, split where one polynomial cannot follow
// the segment.
TEST(StrutLawGeneral, HelixTurnsAndBlendsArePolynomialsWithinTheTolerance) {
  const Machine machine = ch5_hexapod();
  const auto program = test::gcode_for(machine,
                                       "G21 G90 G17\n"
                                       "G0 X20 Y0 Z0\n"
                                       "G3 X20 Y0 Z-4 I-20 J0 F800\n"  // line 3: one helical turn
                                       "G1 X30 A4 B-3 C5 F600\n"       // line 4: turns while it moves
                                       "G1 A-2\n"                      // line 5: rotation only
                                       "G1 Y20\n"                      // line 6
                                       "G1 X10 Y25\n"                  // line 7: corner blends at 6/7, 7/8
                                       "G1 X0 Y10\n"
                                       "M2\n",
                                       "general.ngc");
  const auto plan = test::plan_or_fail(machine, program);
  const path::Path& path = plan.path;
  const LawFitSettings settings;
  const StrutLaws laws = fit_or_fail(machine, path, settings);
  int helix = 0, turning = 0, rotation_only = 0, blends = 0, tilted_lines = 0;
  for (int p = 0; p < laws.piece_count(); ++p) {
    const path::Segment& seg = path.segments[laws.piece(p).segment];
    const path::Curve& curve = path.curves[seg.curve_a];
    const bool general = seg.is_blend() || seg.rotation_only || curve.rotation_angle_rad > 0.0 ||
                         (curve.kind == path::CurveKind::helix && curve.axial_mm != 0.0);
    if (!general) {  // the lines at constant (tilted, after line 4) orientation keep the closed model
      EXPECT_EQ(laws.model(p), LawModel::sqrt_quadratic) << "line " << laws.line(p);
      EXPECT_LT(laws.piece(p).fit_error, 1e-9) << "line " << laws.line(p);
      tilted_lines += curve.start_rotation.angularDistance(Eigen::Quaterniond::Identity()) > 0.01 ? 1 : 0;
      continue;
    }
    EXPECT_EQ(laws.model(p), LawModel::polynomial) << "line " << laws.line(p);
    EXPECT_LE(laws.piece(p).fit_error, settings.tolerance) << "line " << laws.line(p);
    EXPECT_LE(law_deviation(machine, path, laws, laws.piece(p).s_start, laws.piece(p).s_end, 41),
              settings.tolerance)
        << "line " << laws.line(p);
    blends += seg.is_blend() ? 1 : 0;
    rotation_only += seg.rotation_only ? 1 : 0;
    helix += !seg.is_blend() && curve.kind == path::CurveKind::helix ? 1 : 0;
    turning += !seg.is_blend() && !seg.rotation_only && curve.rotation_angle_rad > 0.0 ? 1 : 0;
  }
  EXPECT_GT(helix, 1) << "one degree-6 polynomial cannot follow a whole turn within 9e-6 mm";
  EXPECT_GE(turning, 1);
  EXPECT_GE(rotation_only, 1);
  EXPECT_GE(blends, 2);
  EXPECT_GE(tilted_lines, 3);
  EXPECT_LE(laws.report().max_fit_error, settings.tolerance);
  RecordProperty("general_max_fit_error_mm", fmt::format("{:.3g}", laws.report().max_fit_error));
  RecordProperty("general_pieces", laws.report().pieces);
}

// Fitted and exact laws agree at random s on the shipped example programs.
TEST(StrutLawExamples, FittedAgreesWithExactOnPocketAndHelix) {
  const Machine machine = ch5_hexapod();
  std::mt19937_64 rng(515);
  for (const char* name : {"pocket.ngc", "helix.ngc"}) {
    const auto plan = test::plan_or_fail(machine, example_program(machine, name));
    const path::Path& path = plan.path;
    const LawFitSettings settings;
    const StrutLaws laws = fit_or_fail(machine, path, settings);
    auto exact = StrutLaws::exact(machine, path, name);
    ASSERT_TRUE(exact.ok());
    EXPECT_EQ(exact->piece_count(), static_cast<int>(path.segments.size()));
    EXPECT_EQ(exact->report().exact, exact->piece_count());
    EXPECT_LE(laws.report().max_fit_error, settings.tolerance) << name;
    EXPECT_GT(laws.report().sqrt_quadratic + laws.report().sqrt_fourier, 0) << name;
    double worst = 0.0;
    int hint_fit = 0, hint_exact = 0;
    std::array<double, kMaxActuators> a{}, b{};
    for (int k = 0; k < 2000; ++k) {
      const double s = test::uniform(rng, 0.0, path.length());
      ASSERT_TRUE(laws.evaluate(s, hint_fit, a.data()));
      ASSERT_TRUE(exact->evaluate(s, hint_exact, b.data()));
      const ActuatorVector reference = ik_at(machine, path, s);
      for (int j = 0; j < 6; ++j) {
        worst = std::max(worst, std::abs(a[j] - b[j]));
        ASSERT_EQ(b[j], reference[j]) << name << " s = " << s;
      }
    }
    EXPECT_LE(worst, settings.tolerance) << name;
    // A monotone sweep with a running hint finds the same pieces as a fresh search.
    int running = 0;
    for (int k = 0; k <= 5000; ++k) {
      const double s = path.length() * k / 5000.0;
      int fresh = laws.piece_count() - 1;
      ASSERT_TRUE(laws.evaluate(s, running, a.data()));
      ASSERT_TRUE(laws.evaluate(s, fresh, b.data()));
      ASSERT_EQ(running, fresh) << name << " s = " << s;
      ASSERT_LE(laws.piece(running).s_start, s);
      for (int j = 0; j < 6; ++j) ASSERT_EQ(a[j], b[j]);
    }
    RecordProperty(std::string(name) + "_max_fit_error_mm",
                   fmt::format("{:.3g}", laws.report().max_fit_error));
  }
}

// Mechanisms whose actuators are no hexapod strut lengths get polynomials, and their errors are reported.
TEST(StrutLawOtherMechanisms, PlanarAndTripodArePolynomialAndReportTheirErrors) {
  Machine planar = test::machine_from_example("examples/machines/planar3.yaml");
  planar.limits.speed = 100.0;
  planar.limits.accel = 1000.0;
  Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  const std::string tripod_text =  // a tripod controls Z, A and B
      "G21 G90 G17\nG0 Z0 A0 B0\nG1 Z-3 A2 F1200\nG1 B-2\nG1 Z5 A-2 B2 F2000\nG1 Z0 A0 B0\nM2\n";
  struct Case {
    const Machine* machine;
    program::CanonicalProgram program;
    int actuators;
  };
  const Case cases[] = {{&planar, example_program(planar, "planar_circle.ngc"), 3},
                        {&tripod, test::gcode_for(tripod, tripod_text, "tripod.ngc"), 3}};
  const LawFitSettings settings;
  for (const Case& c : cases) {
    const auto plan = test::plan_or_fail(*c.machine, c.program);
    const StrutLaws laws = fit_or_fail(*c.machine, plan.path, settings);
    const auto& report = laws.report();
    EXPECT_EQ(laws.actuator_count(), c.actuators);
    EXPECT_GT(report.pieces, 0);
    EXPECT_EQ(report.polynomial, report.pieces) << c.machine->name;
    double largest = 0.0;
    int largest_line = 0;
    for (int p = 0; p < laws.piece_count(); ++p) {
      if (laws.piece(p).fit_error > largest) {
        largest = laws.piece(p).fit_error;
        largest_line = laws.line(p);
      }
    }
    EXPECT_EQ(report.max_fit_error, largest) << c.machine->name;
    EXPECT_EQ(report.max_fit_error_line, largest_line) << c.machine->name;
    EXPECT_GT(report.max_fit_error, 0.0) << c.machine->name;
    EXPECT_LE(report.max_fit_error, settings.tolerance) << c.machine->name;
    EXPECT_LE(law_deviation(*c.machine, plan.path, laws, 0.0, plan.path.length(), 1501), settings.tolerance)
        << c.machine->name;
    RecordProperty(c.machine->name + "_max_fit_error", fmt::format("{:.3g}", report.max_fit_error));
  }
}

// s outside [0, length] is clamped; a path without segments gives its start's IK.
TEST(StrutLawEnds, EvaluationClampsToThePathAndAnEmptyPathIsItsStart) {
  const Machine machine = ch5_hexapod();
  const auto plan = test::plan_or_fail(machine, example_program(machine, "ch5_line.ngc"));
  const path::Path& path = plan.path;
  const StrutLaws laws = fit_or_fail(machine, path);
  ASSERT_EQ(laws.length(), path.length());
  std::array<double, kMaxActuators> below{}, at_start{}, above{}, at_end{};
  int hint = 0;
  ASSERT_TRUE(laws.evaluate(-25.0, hint, below.data()));
  ASSERT_TRUE(laws.evaluate(0.0, hint, at_start.data()));
  ASSERT_TRUE(laws.evaluate(path.length() + 25.0, hint, above.data()));
  ASSERT_TRUE(laws.evaluate(path.length(), hint, at_end.data()));
  const ActuatorVector start = ik_at(machine, path, 0.0);
  const ActuatorVector end = ik_at(machine, path, path.length());
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(below[j], at_start[j]);
    EXPECT_EQ(above[j], at_end[j]);
    EXPECT_NEAR(at_start[j], start[j], 1e-9);
    EXPECT_NEAR(at_end[j], end[j], 1e-9);
  }
  // The ch5 line ends at (50, 0, 700), level: the mirror image of the start's lengths (Smirnov 2019, §5.2.5).
  EXPECT_NEAR(at_end[0], 586.3074649620, 1e-9);
  EXPECT_NEAR(at_end[3], 623.7911728446, 1e-9);

  path::Path empty;
  empty.start.position_mm = Eigen::Vector3d(-50.0, 0.0, 700.0);
  empty.start.rotation = Eigen::Quaterniond::Identity();
  const StrutLaws fitted = fit_or_fail(machine, empty);
  auto exact = StrutLaws::exact(machine, empty, "empty");
  ASSERT_TRUE(exact.ok());
  EXPECT_EQ(fitted.piece_count(), 0);
  EXPECT_EQ(fitted.length(), 0.0);
  const std::array<double, 6> e2 = {623.7911728445, 607.5487036598, 603.1222458757,
                                    586.3074649620, 588.5880863511, 621.6397151039};
  for (const StrutLaws* l : {&fitted, static_cast<const StrutLaws*>(&*exact)}) {
    std::array<double, kMaxActuators> q{};
    int h = 3;
    ASSERT_TRUE(l->evaluate(12.0, h, q.data()));
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(q[j], e2[j], 1e-9) << j;
  }
}

// §5.2.2: the arc law may be replaced locally by a quadratic while |φ| < 0.1 rad. On the fitted arc of the
// ch5 hexapod: the remainder of the 2nd-order Taylor expansion of L(φ) = sqrt(a0 + a1 cos φ + b1 sin φ) stays
// below 1 % of the law's first-order scale (the largest slope its harmonic can give, A/(2L) with A the
// harmonic's amplitude) for |φ| ≤ 0.1, and exceeds it further out (|φ| ≤ 0.5), at any point of the arc.
TEST(StrutLawArc, QuadraticReplacementHoldsForPhiBelowATenthRadian) {
  const Machine machine = ch5_hexapod();
  const auto program =
      test::gcode_for(machine, "G21 G90 G17\nG0 X-70 Y0 Z-100\nG3 X70 Y0 I70 J0 F1000\nM2\n", "e11.ngc");
  const auto plan = test::plan_or_fail(machine, program);
  const StrutLaws laws = fit_or_fail(machine, plan.path);
  const auto arcs = pieces_where(laws, plan.path, [&](const path::Segment& seg) {
    return path::CurveKind::helix == plan.path.curves[seg.curve_a].kind;
  });
  ASSERT_EQ(arcs.size(), 1u);
  const int p = arcs[0];
  ASSERT_EQ(laws.model(p), LawModel::sqrt_fourier);
  const auto& piece = laws.piece(p);
  const double angle_per_s = piece.angle_per_u * piece.u_per_s;
  // Half a circle, less what the corner blend at its start takes: centres ± φ stay within ±1.5 rad.
  ASSERT_GT(std::abs(angle_per_s) * (piece.s_end - piece.s_start), 3.1);
  std::array<double, kMaxActuators> q{};
  auto law = [&](int j, double theta) {
    int hint = p;
    EXPECT_TRUE(laws.evaluate(piece.s_mid + theta / angle_per_s, hint, q.data()));
    return q[j];
  };
  auto worst_ratio = [&](double phi_max) {
    double worst = 0.0;
    for (int j = 0; j < 6; ++j) {
      const auto c = laws.coefficients(p, j);
      const double amplitude = std::hypot(c[1], c[2]);              // of −c1 cos θ + c2 sin θ
      for (double centre = -1.0; centre <= 1.0; centre += 0.125) {  // rad from the arc's middle
        const double h = 1e-3;
        const double l0 = law(j, centre), lp = law(j, centre + h), lm = law(j, centre - h);
        const double d1 = (lp - lm) / (2 * h), d2 = (lp - 2 * l0 + lm) / (h * h);
        const double scale = amplitude / (2.0 * l0);
        for (double phi = -phi_max; phi <= phi_max + 1e-12; phi += phi_max / 8) {
          if (phi == 0.0) continue;
          const double remainder = law(j, centre + phi) - (l0 + d1 * phi + 0.5 * d2 * phi * phi);
          worst = std::max(worst, std::abs(remainder) / (scale * std::abs(phi)));
        }
      }
    }
    return worst;
  };
  const double within = worst_ratio(0.1);
  const double beyond = worst_ratio(0.5);
  RecordProperty("cubic_share_at_0.1_rad", fmt::format("{:.3g}", within));
  RecordProperty("cubic_share_at_0.5_rad", fmt::format("{:.3g}", beyond));
  EXPECT_LT(within, 0.01);
  EXPECT_GT(beyond, 0.01);
}

// IK failing at a sample names the source and the segment's line; bad settings are refused.
TEST(StrutLawErrors, UnreachableSampleNamesTheLineAndBadSettingsAreRefused) {
  // The hexaglide's struts have a constant 800 mm: 900 mm below home they cannot reach the rails.
  const Machine machine = test::machine_from_example("examples/machines/hexaglide.yaml");
  path::Path path;
  path.start.position_mm = machine.mechanism->home().position_mm;
  const Eigen::Quaterniond level(machine.mechanism->home().rotation);
  path.start.rotation = level;
  path.curves.push_back(path::make_line(
      path.start.position_mm, path.start.position_mm - Eigen::Vector3d(0.0, 0.0, 900.0), level, level));
  path::Segment segment;
  segment.length = path.curves[0].param_length;
  segment.line = 42;
  path.segments.push_back(segment);
  auto refused = StrutLaws::fit(machine, path, {}, "bad.ngc");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::unreachable);
  EXPECT_NE(refused.error().message.find("bad.ngc:42:"), std::string::npos) << refused.error().message;
  auto exact = StrutLaws::exact(machine, path, "bad.ngc");
  ASSERT_TRUE(exact.ok());
  std::array<double, kMaxActuators> q{};
  int hint = 0;
  EXPECT_TRUE(exact->evaluate(0.0, hint, q.data()));
  EXPECT_FALSE(exact->evaluate(path.length(), hint, q.data())) << "exact laws report IK failing";

  std::vector<LawFitSettings> bad_settings(4);
  bad_settings[0].tolerance = 0.0;
  bad_settings[1].polynomial_degree = 0;
  bad_settings[2].check_points = 0;
  bad_settings[3].min_piece_length = 0.0;
  for (const LawFitSettings& bad : bad_settings) {
    auto result = StrutLaws::fit(machine, path, bad, "bad.ngc");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::bad_input) << result.error().message;
  }
}

// Neighbouring pieces meet: the polynomial interpolates IK at both ends of its piece and the closed models
// are exact, so the laws have no step at a piece boundary (to round-off), although a piece's interior may be
// off by up to the tolerance.
TEST(StrutLawPieces, NeighbouringPiecesJoinWithoutAStep) {
  const Machine machine = ch5_hexapod();
  const auto plan = test::plan_or_fail(machine, example_program(machine, "pocket.ngc"));
  const StrutLaws laws = fit_or_fail(machine, plan.path);
  ASSERT_GT(laws.report().polynomial, 10);
  ASSERT_GT(laws.report().max_fit_error, 1e-7) << "the interiors are not exact, so the test has teeth";
  std::array<double, kMaxActuators> left{}, right{};
  double worst_step = 0.0;
  for (int p = 0; p + 1 < laws.piece_count(); ++p) {
    const auto& a = laws.piece(p);
    const auto& b = laws.piece(p + 1);
    ASSERT_EQ(a.s_end, b.s_start) << p;
    interpolation::evaluate_fitted_piece(a, laws.coefficients(p, 0).data(), 6, a.s_end, left.data());
    interpolation::evaluate_fitted_piece(b, laws.coefficients(p + 1, 0).data(), 6, b.s_start, right.data());
    for (int j = 0; j < 6; ++j) worst_step = std::max(worst_step, std::abs(left[j] - right[j]));
  }
  RecordProperty("largest_step_mm", fmt::format("{:.3g}", worst_step));
  EXPECT_LT(worst_step, 1e-9);
}

// A coarse tolerance that no piece can meet stops the splitting at the minimum length and reports the error
// instead of failing.
TEST(StrutLawErrors, SplittingStopsAtTheMinimumPieceLengthAndReportsTheError) {
  const Machine machine = ch5_hexapod();
  const auto program =
      test::gcode_for(machine, "G21 G90 G17\nG0 X20 Y0 Z0\nG3 X20 Y0 Z-4 I-20 J0 F800\nM2\n", "coarse.ngc");
  const auto plan = test::plan_or_fail(machine, program);
  LawFitSettings settings;
  settings.polynomial_degree = 1;
  settings.tolerance = 1e-12;
  settings.min_piece_length = 10.0;
  const StrutLaws laws = fit_or_fail(machine, plan.path, settings);
  const auto& report = laws.report();
  EXPECT_GT(report.max_fit_error, settings.tolerance);
  EXPECT_EQ(report.max_fit_error_line, 3);
  for (int p = 0; p < laws.piece_count(); ++p) {
    const double length = laws.piece(p).s_end - laws.piece(p).s_start;
    if (laws.model(p) != LawModel::polynomial) continue;
    const path::Segment& seg = plan.path.segments[laws.piece(p).segment];
    EXPECT_LT(length, 2.0 * settings.min_piece_length) << p;  // split as far as allowed, not further:
    if (length < seg.length - 1e-9) {  // a piece smaller than its segment (s values are running sums)
      EXPECT_GE(length, settings.min_piece_length) << p;
    }
  }
}

}  // namespace
}  // namespace pkm
