// NX NURBS records: the clamped cubic B-spline reading (a Bézier when there are no interior knots), line
// moves within the chord tolerance ending exactly at the last CNTRL, chaining, and the checks of the record.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "program/cl_reader_nurbs.hpp"
#include "program/part_program.hpp"

namespace pkm::program {
namespace cl_nurbs_test {

constexpr double kNurbsTestToleranceMm = 0.001;  // the reader's chord tolerance

Result<CanonicalProgram> nurbs_read(const std::string& text) {
  InterpretOptions options;
  options.format = ProgramFormat::nx;
  return read_cl_data(text, "test.cls", options);
}

std::string nurbs_record(const Eigen::Vector3d& start, const std::vector<double>& knots,
                         const std::vector<Eigen::Vector3d>& control) {
  std::ostringstream out;
  out.precision(17);
  out << "FEDRAT/MMPM,600\nGOTO/" << start.x() << ',' << start.y() << ',' << start.z() << "\nNURBS/\n";
  for (std::size_t i = 0; i < knots.size(); i += 12) {  // NX: at most 12 knots a record
    out << "KNOT/";
    for (std::size_t j = i; j < std::min(knots.size(), i + 12); ++j) out << (j > i ? "," : "") << knots[j];
    out << '\n';
  }
  for (const Eigen::Vector3d& p : control) out << "CNTRL/" << p.x() << ',' << p.y() << ',' << p.z() << '\n';
  return out.str();
}

Eigen::Vector3d bezier(const std::array<Eigen::Vector3d, 4>& p, double t) {
  const double s = 1.0 - t;
  return s * s * s * p[0] + 3 * s * s * t * p[1] + 3 * s * t * t * p[2] + t * t * t * p[3];
}

TEST(ClNurbs, WithoutInteriorKnotsTheSplineIsTheBezier) {
  ClCubicSpline spline;
  const std::array<Eigen::Vector3d, 4> p = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 3, 0),
                                            Eigen::Vector3d(4, -2, 1), Eigen::Vector3d(5, 1, 2)};
  spline.points.assign(p.begin(), p.end());
  spline.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    EXPECT_LT((spline.at(t) - bezier(p, t)).norm(), 1e-12) << t;
  }
}

// Random splines: every chord within the tolerance of the curve between its ends (densely sampled).
TEST(ClNurbs, EveryChordIsWithinTheTolerance) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  for (int trial = 0; trial < 10; ++trial) {
    ClCubicSpline spline;
    const int n = 4 + trial;
    for (int i = 0; i <= n; ++i)
      spline.points.emplace_back(coordinate(random), coordinate(random), coordinate(random));
    spline.knots = {0, 0, 0, 0};
    for (int i = 1; i <= n - 3; ++i) spline.knots.push_back(double(i) / (n - 2));
    spline.knots.insert(spline.knots.end(), {1, 1, 1, 1});
    const std::vector<double> ts = cl_spline_chord_parameters(spline, kNurbsTestToleranceMm);
    ASSERT_GE(ts.size(), 2u);
    EXPECT_EQ(ts.front(), 0.0);
    EXPECT_EQ(ts.back(), 1.0);
    double worst = 0.0;
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const Eigen::Vector3d a = spline.at(ts[i - 1]), b = spline.at(ts[i]);
      for (int k = 1; k < 20; ++k) {
        const Eigen::Vector3d c = spline.at(ts[i - 1] + (ts[i] - ts[i - 1]) * k / 20.0);
        const double u = std::clamp((c - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
        worst = std::max(worst, (c - (a + u * (b - a))).norm());
      }
    }
    EXPECT_LE(worst, kNurbsTestToleranceMm);
    EXPECT_GT(worst, kNurbsTestToleranceMm / 20);  // and not absurdly many segments
  }
}

TEST(ClNurbs, ReadAsLinesThatEndAtTheLastControlPoint) {
  const std::vector<Eigen::Vector3d> control = {{10, 5, 0}, {20, -5, 0}, {30, 5, 0}, {40, 0, 0}, {50, 2, 0}};
  auto program =
      nurbs_read(nurbs_record({0, 0, 0}, {0.25, 0.6, 1.0}, control) + "PAINT/COLOR,31\nGOTO/60,0,0\n");
  ASSERT_TRUE(program) << program.error().message;
  const auto& moves = program.value().moves;
  ASSERT_GT(moves.size(), 10u);
  // moves[0] is the GOTO before NURBS; the last is the GOTO after it.
  const CanonicalMove& end = moves[moves.size() - 2];
  EXPECT_EQ(end.end_mm, control.back());
  for (std::size_t i = 1; i + 1 < moves.size(); ++i) {
    EXPECT_EQ(moves[i].kind, MoveKind::line);
    EXPECT_EQ(moves[i].line, 3);  // the NURBS statement
    EXPECT_EQ(moves[i].feed_mm_min, 600.0);
    EXPECT_EQ(moves[i].end_mm.z(), 0.0);  // control points in a plane: the curve in it
  }
  EXPECT_EQ(moves.back().end_mm, Eigen::Vector3d(60, 0, 0));
  EXPECT_EQ(moves.back().line, 11);
}

TEST(ClNurbs, ControlPointsOnALineOrAPlaneKeepTheCurveOnIt) {
  const Eigen::Vector3d origin(1, 2, 3), u = Eigen::Vector3d(1, 2, 2) / 3.0,
                                         v = Eigen::Vector3d(2, -2, 1) / 3.0;
  std::vector<Eigen::Vector3d> on_line, on_plane;
  const double s[] = {3, 1, 7, 12, 20, 25};
  for (int i = 0; i < 6; ++i) {
    on_line.push_back(origin + s[i] * u);
    on_plane.push_back(origin + s[i] * u + (i % 2 ? 4.0 : -3.0) * v);
  }
  const std::vector<double> knots = {0.2, 0.4, 0.7, 1.0};
  for (const auto* control : {&on_line, &on_plane}) {
    auto program = nurbs_read(nurbs_record(origin, knots, *control));
    ASSERT_TRUE(program) << program.error().message;
    const Eigen::Vector3d normal = u.cross(v);
    for (const CanonicalMove& m : program.value().moves) {
      const Eigen::Vector3d d = m.end_mm - origin;
      EXPECT_LT(std::abs(d.dot(normal)), 1e-9);
      if (control == &on_line) {
        EXPECT_LT(std::abs(d.dot(v)), 1e-9);
      }
    }
  }
}

TEST(ClNurbs, ConsecutiveCurvesChainAndTheFileMayEndInOne) {
  const std::string first =
      nurbs_record({0, 0, 0}, {0.5, 1.0}, {{5, 5, 0}, {10, 5, 0}, {15, 0, 0}, {20, 0, 0}});
  const std::string second = "NURBS/\nKNOT/1.0\nCNTRL/25,0,0\nCNTRL/30,5,0\nCNTRL/35,5,1\n";
  auto program = nurbs_read(first + second);
  ASSERT_TRUE(program) << program.error().message;
  const auto& moves = program.value().moves;
  EXPECT_EQ(moves.back().end_mm, Eigen::Vector3d(35, 5, 1));
  EXPECT_EQ(moves.back().line, 9);
  bool through_joint = false;
  for (const CanonicalMove& m : moves) through_joint |= m.end_mm == Eigen::Vector3d(20, 0, 0);
  EXPECT_TRUE(through_joint);
}

std::string nurbs_error_of(const std::string& text) {
  auto program = nurbs_read(text);
  if (program) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  return program.error().message;
}

TEST(ClNurbs, RecordsThatAreNotNxsCubicAreErrorsAtTheNurbsLine) {
  const std::vector<Eigen::Vector3d> four = {{1, 0, 0}, {2, 1, 0}, {3, 0, 0}, {4, 0, 0}};
  EXPECT_EQ(nurbs_error_of(nurbs_record({0, 0, 0}, {0.5, 0.7, 1.0}, four)),
            "test.cls:3:1: a NURBS with 4 CNTRL points lists 3 knots (KNOT), 2 expected (CNTRLs − 2)");
  EXPECT_EQ(nurbs_error_of(nurbs_record({0, 0, 0}, {0.5, 0.9}, four)),
            "test.cls:3:1: the last knot of a NURBS must be 1, got 0.9");
  EXPECT_EQ(nurbs_error_of(nurbs_record({0, 0, 0}, {0.7, 0.5, 1.0},
                                        {{1, 0, 0}, {2, 1, 0}, {3, 0, 0}, {4, 0, 0}, {5, 0, 0}})),
            "test.cls:3:1: NURBS knots fall: 0.5 after 0.7");
  EXPECT_EQ(nurbs_error_of(nurbs_record({0, 0, 0}, {1.0}, {{1, 0, 0}, {2, 1, 0}})),
            "test.cls:3:1: a NURBS (cubic) needs at least 3 CNTRL points, got 2");
  EXPECT_EQ(nurbs_error_of("FEDRAT/100\nGOTO/0,0,0\nNURBS/\nKNOT/1.0\nCNTRL/1,0,0\nKNOT/1.0\n"),
            "test.cls:6:1: KNOT after CNTRL: a NURBS lists all its knots first");
  EXPECT_EQ(nurbs_error_of("FEDRAT/100\nGOTO/0,0,0\nNURBS/\nKNOT/1.0\nCNTRL/1,0\n"),
            "test.cls:5:1: CNTRL takes x,y,z (3 values), got 2");
  EXPECT_EQ(nurbs_error_of("FEDRAT/100\nGOTO/0,0,0\nNURBS/3\n"),
            "test.cls:3:7: NURBS/ takes no values (its KNOT/ and CNTRL/ records follow)");
  EXPECT_EQ(nurbs_error_of("RAPID\nGOTO/0,0,0\nNURBS/\nKNOT/0.5,1.0\nCNTRL/1,0,0\nCNTRL/2,0,0\nCNTRL/3,0,0\n"
                           "CNTRL/4,0,0\n"),
            "test.cls:3:1: cutting move before any feed rate (FEDRAT)");
}

}  // namespace cl_nurbs_test
}  // namespace pkm::program
