// CL CYCLE/…: every CAM system's form gives the moves of the equivalent G-code canned cycle (the same
// engine), along any tool axis; variable pecks; errors that name line and column.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "program/part_program.hpp"

namespace pkm::program {
namespace cl_cycle_test {

CanonicalProgram cycle_read_cl(const std::string& text, ProgramFormat format = ProgramFormat::apt) {
  InterpretOptions options;
  options.format = format;
  auto program = read_cl_data(text, "test.cl", options);
  if (!program) {
    ADD_FAILURE() << program.error().message << "\n" << text;
    return {};
  }
  return std::move(program.value());
}

CanonicalProgram cycle_read_gcode(const std::string& text) {
  auto program = interpret_gcode(text, "test.ngc");
  if (!program) {
    ADD_FAILURE() << program.error().message << "\n" << text;
    return {};
  }
  return std::move(program.value());
}

std::string cycle_error_of(const std::string& text) {
  InterpretOptions options;
  options.format = ProgramFormat::apt;
  auto program = read_cl_data(text, "test.cl", options);
  if (program) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  return program.error().message;
}

// The same moves: kinds, end points (after `rotation`), feeds and dwells.
void expect_same_moves(const CanonicalProgram& cl, const CanonicalProgram& gcode,
                       const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  ASSERT_EQ(cl.moves.size(), gcode.moves.size());
  for (std::size_t i = 0; i < cl.moves.size(); ++i) {
    const CanonicalMove& a = cl.moves[i];
    const CanonicalMove& b = gcode.moves[i];
    EXPECT_EQ(a.kind, b.kind) << "move " << i;
    EXPECT_LT((a.end_mm - rotation * b.end_mm).norm(), 1e-9)
        << "move " << i << ": " << a.end_mm.transpose() << " vs " << (rotation * b.end_mm).transpose();
    if (a.kind == MoveKind::line) {
      EXPECT_DOUBLE_EQ(a.feed_mm_min, b.feed_mm_min) << "move " << i;
    }
    if (a.kind == MoveKind::dwell) {
      EXPECT_DOUBLE_EQ(a.dwell_s, b.dwell_s) << "move " << i;
    }
  }
}

struct CycleCase {
  std::string cl_definition;  // the CYCLE statement
  std::string gcode_cycle;    // the G-code block drilling the first hole (X10 Y20), the second is X40
};

// Two holes with their tops at z = 0 under a clearance point at z = 30.
std::string cycle_cl_program(const std::string& definition) {
  return "SPINDL/RPM,500,CLW\nRAPID\nGOTO/10,20,30\n" + definition +
         "\nGOTO/10,20,0\nGOTO/40,20,0\nCYCLE/OFF\n";
}

std::string cycle_gcode_program(const std::string& cycle) {
  return "G21 G17 G90 S500 M3\nG0 X10 Y20 Z30\n" + cycle + "\nX40\nG80\nM2\n";
}

TEST(ClCycle, EveryFormDrillsAsTheEquivalentGcodeCycle) {
  const std::vector<CycleCase> cases = {
      // SolidWorks CAM
      {"CYCLE/DRILL,FEDTO,8.,MMPM,250.,RAPTO,3.,RTRCTO,30.,DWELL,0", "G98 G81 X10 Y20 Z-8 R3 F250"},
      {"CYCLE/DRILL,FEDTO,8.,MMPM,250.,RAPTO,3.,RTRCTO,30.,DWELL,.5", "G98 G82 X10 Y20 Z-8 R3 P0.5 F250"},
      {"CYCLE/DEEP,FEDTO,8.,INCR,2.5,MMPM,250.,RAPTO,3.,RTRCTO,30.", "G98 G83 X10 Y20 Z-8 R3 Q2.5 F250"},
      {"CYCLE/DEEP2,FEDTO,8.,1STPECK,2.5,SUBPECK,2.5,MMPM,250.,RAPTO,3.,RTRCTO,30.",
       "G98 G83 X10 Y20 Z-8 R3 Q2.5 F250"},
      // NX
      {"CYCLE/DRILL,RAPTO,3.0000,FEDTO,8.0000,MMPM,250.0000", "G99 G81 X10 Y20 Z-8 R3 F250"},
      {"CYCLE/DRILL,DEEP,RAPTO,3.0000,FEDTO,8.0000,STEP,2.0000,MMPM,250.0000",
       "G99 G83 X10 Y20 Z-8 R3 Q2 F250"},
      {"CYCLE/DRILL,RAPTO,3.0000,FEDTO,8.0000,RTRCTO,AUTO,MMPM,250.0000", "G98 G81 X10 Y20 Z-8 R3 F250"},
      // Pro/CLfile
      {"CYCLE / DEEP, DEPTH, 8.000000, STEP, 2.500000, MMPM, 250.000000, CLEAR,$\n 3.000000",
       "G99 G83 X10 Y20 Z-8 R3 Q2.5 F250"},
      // CAMWorks (blank-separated values)
      {"CYCLE/ DRILL,G98,8.000000,PECKING,2.500000,2.500000,MMPM,250.000000,3.000000,30.000000 30.000000 "
       "DWELL,0.000000",
       "G98 G83 X10 Y20 Z-8 R3 Q2.5 F250"},
      // generic APT
      {"CYCLE/DRILL,8,MMPM,250,3", "G99 G81 X10 Y20 Z-8 R3 F250"},
      {"CYCLE/DRILL,8,IPM,10,3", "G99 G81 X10 Y20 Z-8 R3 F254"},
      {"CYCLE/FACE,8,MMPM,250,3,DWELL,2", "G99 G82 X10 Y20 Z-8 R3 P2 F250"},
      {"CYCLE/DEEP,8,MMPM,250,3,STEP,2", "G99 G83 X10 Y20 Z-8 R3 Q2 F250"},
      {"CYCLE/BRKCHP,8,MMPM,250,3,STEP,2", "G99 G73 X10 Y20 Z-8 R3 Q2 F250"},
      {"CYCLE/TAP,8,MMPM,250,3", "G99 G84 X10 Y20 Z-8 R3 F250"},
      {"CYCLE/BORE,8,MMPM,250,3", "G99 G85 X10 Y20 Z-8 R3 F250"},
      {"CYCLE/REAM,8,MMPR,0.5,3", "G99 G85 X10 Y20 Z-8 R3 F250"},
  };
  for (const CycleCase& c : cases) {
    SCOPED_TRACE(c.cl_definition);
    const CanonicalProgram cl = cycle_read_cl(cycle_cl_program(c.cl_definition));
    const CanonicalProgram gcode = cycle_read_gcode(cycle_gcode_program(c.gcode_cycle));
    expect_same_moves(cl, gcode);
    for (std::size_t i = 3; i < cl.moves.size(); ++i) {  // the holes' moves: their GOTO's line
      EXPECT_GE(cl.moves[i].line, 5);
      EXPECT_EQ(cl.moves[i].orientation, OrientationSource::tool_axis);
    }
  }
}

TEST(ClCycle, TappingSendsTheSpindleEvents) {
  const CanonicalProgram cl = cycle_read_cl(cycle_cl_program("CYCLE/TAP,8,MMPM,250,3"));
  std::vector<std::string> spindle;
  for (const ProgramEvent& e : cl.events)
    if (e.what.starts_with("M")) spindle.push_back(e.what);
  const std::vector<std::string> one_hole = {"M5", "M4 S500", "M5", "M3 S500"};
  std::vector<std::string> expected = one_hole;
  expected.insert(expected.end(), one_hole.begin(), one_hole.end());
  EXPECT_EQ(spindle, expected);
}

std::string cycle_goto(const Eigen::Vector3d& p, const Eigen::Vector3d& axis) {
  std::ostringstream out;
  out.precision(17);
  out << "GOTO/" << p.x() << ',' << p.y() << ',' << p.z() << ',' << axis.x() << ',' << axis.y() << ','
      << axis.z() << '\n';
  return out.str();
}

// The drilling depends on the tool axis and the hole points only: turn both and the moves turn with them.
TEST(ClCycle, ATiltedToolAxisGivesTheMovesRotated) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  const std::vector<std::string> definitions = {
      "CYCLE/DEEP2,FEDTO,8.,1STPECK,3.,SUBPECK,2.,MMPM,250.,RAPTO,3.,RTRCTO,25.",
      "CYCLE/DRILL,RAPTO,3.0000,FEDTO,8.0000,MMPM,250.0000",
      "CYCLE/BRKCHP,8,MMPM,250,3,STEP,2",
  };
  for (const std::string& definition : definitions) {
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Quaterniond q =
          Eigen::Quaterniond(gauss(random), gauss(random), gauss(random), gauss(random)).normalized();
      const Eigen::Matrix3d rotation = q.toRotationMatrix();
      auto program = [&](const Eigen::Matrix3d& r) {
        const Eigen::Vector3d axis = r * Eigen::Vector3d::UnitZ();
        return "RAPID\n" + cycle_goto(r * Eigen::Vector3d(10, 20, 30), axis) + definition + "\n" +
               cycle_goto(r * Eigen::Vector3d(10, 20, 0), axis) +
               cycle_goto(r * Eigen::Vector3d(40, 20, -2), axis) + "CYCLE/OFF\n";
      };
      SCOPED_TRACE(definition);
      const CanonicalProgram turned = cycle_read_cl(program(rotation));
      const CanonicalProgram straight = cycle_read_cl(program(Eigen::Matrix3d::Identity()));
      expect_same_moves(turned, straight, rotation);
      for (const CanonicalMove& m : turned.moves) EXPECT_LT((m.tool_axis - rotation.col(2)).norm(), 1e-12);
    }
  }
}

TEST(ClCycle, VariablePecksGoFirstThenLaterPeckBelowR) {
  const CanonicalProgram cl = cycle_read_cl(
      cycle_cl_program("CYCLE/DEEP2,FEDTO,8.,1STPECK,3.,SUBPECK,2.,MMPM,250.,RAPTO,1.,RTRCTO,30."));
  std::vector<double> feeds_z;
  for (const CanonicalMove& m : cl.moves)
    if (m.kind == MoveKind::line && m.end_mm.x() == 10.0) feeds_z.push_back(m.end_mm.z());
  EXPECT_EQ(feeds_z, (std::vector<double>{-2.0, -4.0, -6.0, -8.0}));
  // After each peck: out to R, back down to 0.254 mm above the last depth (G83's way).
  ASSERT_GE(cl.moves.size(), 6u);
  EXPECT_DOUBLE_EQ(cl.moves[3].end_mm.z(), -2.0);
  EXPECT_DOUBLE_EQ(cl.moves[4].end_mm.z(), 1.0);
  EXPECT_NEAR(cl.moves[5].end_mm.z(), -2.0 + 0.254, 1e-12);
  EXPECT_DOUBLE_EQ(cl.moves.back().end_mm.z(), 30.0);  // RTRCTO above the top
}

TEST(ClCycle, RetractToRtrctoAboveEachHoleTop) {
  const CanonicalProgram cl = cycle_read_cl(
      "RAPID\nGOTO/10,20,30\nCYCLE/DRILL,FEDTO,8.,MMPM,250.,RAPTO,3.,RTRCTO,20.,DWELL,0\nGOTO/10,20,-5\n"
      "CYCLE/OFF\n");
  EXPECT_DOUBLE_EQ(cl.moves.back().end_mm.z(), 15.0);
  EXPECT_EQ(cl.moves.back().line, 4);
}

TEST(ClCycle, DeepWithoutAPeckDrillsInOneFeedWithANote) {
  const CanonicalProgram cl = cycle_read_cl(
      cycle_cl_program("CYCLE/DRILL,DEEP,RAPTO,3.0000,FEDTO,8.0000,MMPM,250.0000"), ProgramFormat::nx);
  const CanonicalProgram gcode = cycle_read_gcode(cycle_gcode_program("G99 G81 X10 Y20 Z-8 R3 F250"));
  expect_same_moves(cl, gcode);
  ASSERT_FALSE(cl.notes.empty());
  EXPECT_NE(cl.notes.back().find("no peck"), std::string::npos);
}

TEST(ClCycle, NegativeDepthIsTheSameDepthWithANote) {
  const CanonicalProgram cl = cycle_read_cl(cycle_cl_program("CYCLE/DRILL,RAPTO,3,FEDTO,-8,MMPM,250"));
  const CanonicalProgram gcode = cycle_read_gcode(cycle_gcode_program("G99 G81 X10 Y20 Z-8 R3 F250"));
  expect_same_moves(cl, gcode);
  ASSERT_FALSE(cl.notes.empty());
}

TEST(ClCycle, EventsAndTheStatementsThemselves) {
  const CanonicalProgram cl = cycle_read_cl(
      "RAPID\nGOTO/0,0,10\nCYCLE/INIT\nCYCLE/DRILL,FEDTO,1.,MMPM,100.,RAPTO,1.,RTRCTO,10.,DWELL,0\n"
      "GOTO/0,0,0\nCYCLE/OFF\nCYCLE/CLEAR\nFEDRAT/100\nGOTO/5,0,0\n");
  std::vector<std::string> cycle_events;
  for (const ProgramEvent& e : cl.events)
    if (e.what.starts_with("CYCLE")) cycle_events.push_back(e.what);
  EXPECT_EQ(cycle_events, (std::vector<std::string>{
                              "CYCLE/INIT", "CYCLE/DRILL,FEDTO,1.,MMPM,100.,RAPTO,1.,RTRCTO,10.,DWELL,0",
                              "CYCLE/OFF", "CYCLE/CLEAR"}));
  EXPECT_EQ(cl.moves.back().kind, MoveKind::line);  // after CYCLE/OFF a GOTO is a GOTO again
  EXPECT_EQ(cl.moves.back().end_mm, Eigen::Vector3d(5, 0, 0));
}

TEST(ClCycle, ErrorsNameLineAndColumn) {
  const std::string before = "RAPID\nGOTO/0,0,10\n";
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,FEDTO,8,MMPM,250,RAPTO\n"),
            "test.cl:3:30: RAPTO needs a value");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,FEDTO,8,FOO,3\n"), "test.cl:3:21: unknown CYCLE word 'FOO'");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,FEDTO,x8,MMPM,250,RAPTO,3\n"),
            "test.cl:3:19: bad number 'x8'");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,MMPM,250,RAPTO,3\n"),
            "test.cl:3:7: CYCLE/DRILL needs the depth (FEDTO, DEPTH or the first value)");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,FEDTO,8,MMPM,250\n"),
            "test.cl:3:7: CYCLE/DRILL needs the R clearance (RAPTO, CLEAR)");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/SPOT,8,MMPM,250,3\n").substr(0, 33),
            "test.cl:3:7: unknown cycle 'SPOT'");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,8,MMPM,250,3,4,5\n"),
            "test.cl:3:28: unexpected value '5' in CYCLE");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,8,3\n"),
            "test.cl:3:1: CYCLE/DRILL without a feed (MMPM,f) and no FEDRAT before");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,8,MMPM,250,3\nRAPID\nGOTO/0,0,0\n"),
            "test.cl:5:1: RAPID inside a CYCLE: the cycle makes the holes' moves (CYCLE/OFF missing?)");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,8,MMPM,250,3\nCIRCLE/0,0,0,0,0,1,5\nGOTO/5,0,0\n"),
            "test.cl:5:1: a GOTO after CIRCLE inside a CYCLE (CYCLE/OFF first)");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/TAP,8,MMPM,250,3\nGOTO/0,0,0\n"),
            "test.cl:4:1: Spindle not turning in G84");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/DRILL,8,MMPM,250,-9\nGOTO/0,0,0\n"),
            "test.cl:3:24: the R clearance is below the hole bottom (the depth)");
  EXPECT_EQ(cycle_error_of(before + "CYCLE/OFF,5\n"), "test.cl:3:11: CYCLE/OFF takes no values");
}

}  // namespace cl_cycle_test
}  // namespace pkm::program
