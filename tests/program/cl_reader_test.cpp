// APT CL data reader: every statement kind, the syntax (continuations, comments, case), units, arcs, the tool
// axis carried from statement to statement, and errors that name line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "program/cl_number.hpp"
#include "program/part_program.hpp"
#include "source_paths.hpp"

namespace pkm::program {
namespace {

CanonicalProgram read(std::string_view text, const InterpretOptions& options = {}) {
  auto program = read_cl_data(text, "test.cl", options);
  if (!program) {
    ADD_FAILURE() << program.error().message;
    return {};
  }
  return std::move(program.value());
}

std::string cl_reader_error_of(std::string_view text) {
  auto program = read_cl_data(text, "test.cl");
  if (program) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  EXPECT_EQ(program.error().code, ErrorCode::bad_input);
  return program.error().message;
}

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol = 1e-12) {
  EXPECT_LT((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

TEST(ClReaderNumber, AcceptsTheFormsCamSystemsWrite) {
  EXPECT_EQ(parse_cl_number("1.5"), 1.5);
  EXPECT_EQ(parse_cl_number("-.5"), -0.5);
  EXPECT_EQ(parse_cl_number("2."), 2.0);
  EXPECT_EQ(parse_cl_number("1E-3"), 1e-3);
  EXPECT_EQ(parse_cl_number("1.0000E+02"), 100.0);
  EXPECT_EQ(parse_cl_number("+3"), 3.0);
  EXPECT_EQ(parse_cl_number("-0.0000"), 0.0);
}

TEST(ClReaderNumber, RejectsEverythingElse) {
  for (const char* bad :
       {"", "+", "-", "abc", "1.5.3", "1,5", "inf", "-nan", "--1", "+-1", "1e", "0x10", "1 2"}) {
    EXPECT_FALSE(parse_cl_number(bad).has_value()) << bad;
  }
}

TEST(ClReaderMotion, GotoWithThreeAndSixValues) {
  const auto p = read(
      "FEDRAT/500\n"
      "GOTO/1,2,3\n"
      "GOTO/4,5,6,0,0,2\n");
  ASSERT_EQ(p.moves.size(), 2u);
  const CanonicalMove& first = p.moves[0];
  EXPECT_EQ(first.line, 2);
  EXPECT_EQ(first.kind, MoveKind::line);
  expect_near(first.end_mm, {1, 2, 3});
  EXPECT_EQ(first.orientation, OrientationSource::tool_axis);
  expect_near(first.tool_axis, Eigen::Vector3d::UnitZ());  // no TLAXIS yet: (0,0,1)
  expect_near(first.end_abc_deg, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(first.feed_mm_min, 500.0);
  EXPECT_EQ(p.moves[1].line, 3);
  expect_near(p.moves[1].tool_axis, Eigen::Vector3d::UnitZ());  // (0,0,2) normalised
}

TEST(ClReaderMotion, ToolAxisIsNormalisedAndCarriedOver) {
  const auto p = read(
      "FEDRAT/500\n"
      "GOTO/0,0,0,0,1,1\n"
      "GOTO/1,0,0\n"
      "TLAXIS/3,0,4\n"
      "GOTO/2,0,0\n"
      "GOTO/3,0,0,0,0,1\n"
      "GOTO/4,0,0\n");
  ASSERT_EQ(p.moves.size(), 5u);
  const double h = std::sqrt(0.5);
  expect_near(p.moves[0].tool_axis, {0, h, h});
  expect_near(p.moves[1].tool_axis, {0, h, h});      // previous GOTO's axis
  expect_near(p.moves[2].tool_axis, {0.6, 0, 0.8});  // TLAXIS
  expect_near(p.moves[3].tool_axis, {0, 0, 1});
  expect_near(p.moves[4].tool_axis, {0, 0, 1});
}

TEST(ClReaderMotion, TlaxisBeforeTheFirstGoto) {
  const auto p = read("TLAXIS/0,-1,1\nRAPID\nGOTO/0,0,50\n");
  ASSERT_EQ(p.moves.size(), 1u);
  const double h = std::sqrt(0.5);
  expect_near(p.moves[0].tool_axis, {0, -h, h});
}

TEST(ClReaderMotion, RapidAppliesToTheNextMotionOnly) {
  const auto p = read(
      "FEDRAT/800\n"
      "RAPID\n"
      "GOTO/0,0,10\n"
      "GOTO/0,0,0\n"
      "RAPID\n"
      "GOTO/0,0,10\n");
  ASSERT_EQ(p.moves.size(), 3u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::rapid);
  EXPECT_EQ(p.moves[1].kind, MoveKind::line);
  EXPECT_DOUBLE_EQ(p.moves[1].feed_mm_min, 800.0);
  EXPECT_EQ(p.moves[2].kind, MoveKind::rapid);
}

TEST(ClReaderMotion, RapidNeedsNoFeed) {
  const auto p = read("RAPID\nGOTO/1,2,3\n");
  ASSERT_EQ(p.moves.size(), 1u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::rapid);
}

TEST(ClReaderMotion, StartComesFromTheOptionsOrFrom) {
  InterpretOptions options;
  options.start_mm = {5, 6, 7};
  EXPECT_EQ(read("RAPID\nGOTO/1,2,3\n", options).start_mm, Eigen::Vector3d(5, 6, 7));

  const auto p = read("FROM/10,20,30,0,1,0\nRAPID\nGOTO/1,2,3\n", options);
  expect_near(p.start_mm, {10, 20, 30});
  ASSERT_EQ(p.moves.size(), 1u);  // FROM itself is no motion
  expect_near(p.moves[0].tool_axis, {0, 1, 0});
}

TEST(ClReaderMotion, FromAfterMotionIsARapid) {
  const auto p = read("RAPID\nGOTO/1,2,3\nFROM/4,5,6\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[1].kind, MoveKind::rapid);
  EXPECT_EQ(p.moves[1].line, 3);
  expect_near(p.moves[1].end_mm, {4, 5, 6});
  expect_near(p.start_mm, Eigen::Vector3d::Zero());
}

TEST(ClReaderMotion, DelayIsADwellWhereTheToolIs) {
  const auto p = read("RAPID\nGOTO/1,2,3,0,1,0\nDELAY/2.5\nSPINDL/600\nDELAY/REV,10\n");
  ASSERT_EQ(p.moves.size(), 3u);
  EXPECT_EQ(p.moves[1].kind, MoveKind::dwell);
  EXPECT_DOUBLE_EQ(p.moves[1].dwell_s, 2.5);
  expect_near(p.moves[1].end_mm, {1, 2, 3});
  expect_near(p.moves[1].tool_axis, {0, 1, 0});
  EXPECT_DOUBLE_EQ(p.moves[2].dwell_s, 1.0);  // 10 rev at 600 rpm
}

TEST(ClReaderSyntax, ContinuationLinesJoinOneStatement) {
  const auto p = read(
      "FEDRAT/$\n"
      "  600\n"
      "GOTO/1.0, 2.0, $\n"
      "$$ a comment line inside the statement\n"
      "\n"
      "      3.0, 0.0, $  $$ and a comment after the dollar\n"
      "      0.0, 1.0\n"
      "GOTO/4,5,6\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[0].line, 3);  // the line the statement starts on
  expect_near(p.moves[0].end_mm, {1, 2, 3});
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 600.0);
  EXPECT_EQ(p.moves[1].line, 8);
}

TEST(ClReaderSyntax, ErrorsInContinuationLinesNameThePhysicalLine) {
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1.0,2.0,$\n   3.x\n"), "test.cl:3:4: bad number '3.x'");
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1.0,$\n2.0,$\n  0,0,0,0\n"),
            "test.cl:4:5: the axis vector (i,j,k) has zero length");
}

TEST(ClReaderSyntax, CommentsBlanksCaseAndLineEndings) {
  const auto p = read(
      "$$ NX CLSF\r\n"
      "   \r\n"
      "  fedrat / 250.0 , mmpm  \r\n"
      "\tgoto / 1 , 2 , 3   $$ comment after a statement\r\n"
      "Goto/4,5,6\r\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[0].line, 4);
  expect_near(p.moves[0].end_mm, {1, 2, 3});
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 250.0);
  expect_near(p.moves[1].end_mm, {4, 5, 6});
}

TEST(ClReaderUnits, InchesAreConvertedToMillimetres) {
  const auto p = read(
      "UNITS/INCHES\n"
      "FEDRAT/10\n"
      "FROM/1,0,0\n"
      "GOTO/1,2,3\n"
      "CIRCLE/0,2,3,0,0,1,1\n"
      "GOTO/-1,2,3\n"
      "UNITS/MM\n"
      "GOTO/1,2,3\n");
  expect_near(p.start_mm, {25.4, 0, 0});
  ASSERT_EQ(p.moves.size(), 3u);
  expect_near(p.moves[0].end_mm, {25.4, 50.8, 76.2}, 1e-9);
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 254.0);  // inches per minute
  EXPECT_EQ(p.moves[1].kind, MoveKind::arc);
  expect_near(p.moves[1].center_mm, {0, 50.8, 76.2}, 1e-9);
  expect_near(p.moves[1].end_mm, {-25.4, 50.8, 76.2}, 1e-9);
  expect_near(p.moves[2].end_mm, {1, 2, 3});
  EXPECT_DOUBLE_EQ(p.moves[2].feed_mm_min, 254.0);  // a feed keeps its value in mm/min
}

TEST(ClReaderFeed, PerMinuteForms) {
  const auto feed_of = [](const std::string& fedrat) {
    const auto p = read(fedrat + "\nGOTO/1,0,0\n");
    return p.moves.empty() ? 0.0 : p.moves[0].feed_mm_min;
  };
  EXPECT_DOUBLE_EQ(feed_of("FEDRAT/250"), 250.0);
  EXPECT_DOUBLE_EQ(feed_of("FEDRAT/250,MMPM"), 250.0);
  EXPECT_DOUBLE_EQ(feed_of("FEDRAT/MMPM,250.0000"), 250.0);
  EXPECT_DOUBLE_EQ(feed_of("FEDRAT/10,IPM"), 254.0);
  EXPECT_DOUBLE_EQ(feed_of("FEDRAT/IPM,10"), 254.0);
  EXPECT_DOUBLE_EQ(feed_of("UNITS/INCHES\nFEDRAT/10,MMPM"), 10.0);
}

TEST(ClReaderFeed, PerRevolutionNeedsTheSpindleSpeed) {
  const auto p = read(
      "SPINDL/RPM,1000,CLW\n"
      "FEDRAT/0.1,MMPR\n"
      "GOTO/1,0,0\n"
      "FEDRAT/IPR,.01\n"
      "GOTO/2,0,0\n"
      "SPINDL/2000\n"
      "GOTO/3,0,0\n");
  ASSERT_EQ(p.moves.size(), 3u);
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 100.0);
  EXPECT_NEAR(p.moves[1].feed_mm_min, 254.0, 1e-9);
  EXPECT_NEAR(p.moves[2].feed_mm_min, 508.0, 1e-9);  // per-revolution feed follows the spindle speed
  EXPECT_EQ(
      cl_reader_error_of("LOADTL/1\nFEDRAT/0.1, MMPR\nGOTO/1,0,0\n"),
      "test.cl:2:13: feed per revolution is not supported before a spindle speed is known (SPINDL/rpm)");
}

TEST(ClReaderArc, CounterClockwiseAboutTheGivenAxis) {
  const auto p = read(
      "FROM/10,0,0\n"
      "FEDRAT/300\n"
      "CIRCLE/0,0,0,0,0,1,10\n"
      "GOTO/0,10,0\n"
      "CIRCLE/0,0,0,0,0,-1,10\n"
      "GOTO/10,0,0\n");
  ASSERT_EQ(p.moves.size(), 2u);
  const CanonicalMove& ccw = p.moves[0];
  EXPECT_EQ(ccw.kind, MoveKind::arc);
  EXPECT_EQ(ccw.line, 4);
  expect_near(ccw.center_mm, Eigen::Vector3d::Zero());
  expect_near(ccw.normal, Eigen::Vector3d::UnitZ());
  expect_near(ccw.end_mm, {0, 10, 0});
  EXPECT_EQ(ccw.plane, Plane::xy);
  EXPECT_EQ(ccw.turns, 1);
  EXPECT_DOUBLE_EQ(ccw.feed_mm_min, 300.0);
  expect_near(p.moves[1].normal, -Eigen::Vector3d::UnitZ());  // clockwise seen from +Z
}

TEST(ClReaderArc, CircleAppliesToTheNextGotoOnly) {
  const auto p = read("FROM/10,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,0,1,10\nGOTO/-10,0,0\nGOTO/-10,5,0\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::arc);
  EXPECT_EQ(p.moves[1].kind, MoveKind::line);
}

TEST(ClReaderArc, HelixCentreAtTheStartHeight) {
  // NX appends tolerance and tool values to CIRCLE; they are read as numbers and not used.
  const auto p = read(
      "FROM/20,30,5\n"
      "FEDRAT/300\n"
      "CIRCLE/10.0000,30.0000,-4.0000,0.0000000,0.0000000,1.0000000,10.0000,0.0600,0.5000,10.0000,0.0000\n"
      "GOTO/0,30,2\n");
  ASSERT_EQ(p.moves.size(), 1u);
  expect_near(p.moves[0].center_mm, {10, 30, 5});
  expect_near(p.moves[0].end_mm, {0, 30, 2});
}

TEST(ClReaderArc, ObliqueAxisIsNormalisedAndGetsTheNearestPlane) {
  const double c = std::sqrt(0.5);
  std::ostringstream text;
  // Circle of radius 10 about (1,0,1)/√2 through the centre (0,0,0): start and end at ±10·(0,1,0) rotated.
  text << "FROM/0,10,0\nFEDRAT/300\nCIRCLE/0,0,0,1,0,1,10\nGOTO/" << -10 * c << ",0," << 10 * c << "\n";
  const auto p = read(text.str());
  ASSERT_EQ(p.moves.size(), 1u);
  expect_near(p.moves[0].normal, {c, 0, c});
  EXPECT_EQ(p.moves[0].plane, Plane::xy);
  const auto yz = read("FROM/0,10,0\nFEDRAT/300\nCIRCLE/0,0,0,2,0,0,10\nGOTO/0,0,10\n");
  ASSERT_EQ(yz.moves.size(), 1u);
  EXPECT_EQ(yz.moves[0].plane, Plane::yz);
  expect_near(yz.moves[0].normal, Eigen::Vector3d::UnitX());
  const auto zx = read("FROM/10,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,-1,0,10\nGOTO/0,0,10\n");
  ASSERT_EQ(zx.moves.size(), 1u);
  EXPECT_EQ(zx.moves[0].plane, Plane::zx);
}

TEST(ClReaderArc, ToleratesRoundingButNotAnotherRadius) {
  EXPECT_EQ(read("FROM/10.0001,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,9.9999,0\n").moves.size(), 1u);
  EXPECT_EQ(cl_reader_error_of("FROM/10,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,12,0\n"),
            "test.cl:4:1: CIRCLE: the end point is 12.0000 mm from the axis, the radius is 10.0000 mm");
  EXPECT_EQ(cl_reader_error_of("FROM/11,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n"),
            "test.cl:4:1: CIRCLE: the start point is 11.0000 mm from the axis, the radius is 10.0000 mm");
}

TEST(ClReaderArc, Errors) {
  EXPECT_EQ(cl_reader_error_of("FROM/10,0,0\nFEDRAT/300\nCIRCLE/0,0,0,0,0,1,10\n"),
            "test.cl:3:1: CIRCLE is not followed by the GOTO to its end point");
  EXPECT_EQ(cl_reader_error_of("FROM/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nDELAY/1\n"),
            "test.cl:3:1: DELAY between CIRCLE (line 2) and the GOTO to its end point");
  EXPECT_EQ(cl_reader_error_of("FROM/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nRAPID\nGOTO/0,10,0\n"),
            "test.cl:4:1: RAPID cannot apply to a circular move (CIRCLE)");
  EXPECT_EQ(cl_reader_error_of("CIRCLE/0,0,0,0,0\n"),
            "test.cl:1:1: CIRCLE takes at least 6 values (xc,yc,zc,i,j,k[,r]), got 5");
  EXPECT_EQ(cl_reader_error_of("CIRCLE/0,0,0,0,0,1,10,SIDEWAYS\n"),
            "test.cl:1:23: unknown CIRCLE modifier 'SIDEWAYS'");
  EXPECT_EQ(cl_reader_error_of("CIRCLE/0,0,0,0,0,1,10,TIMES,1.5\n"),
            "test.cl:1:29: TIMES takes a whole number of turns, 1 or more");
  EXPECT_EQ(cl_reader_error_of("CIRCLE/0,0,0,0,0,0,10\n"),
            "test.cl:1:14: the axis vector (i,j,k) has zero length");
  EXPECT_EQ(cl_reader_error_of("CIRCLE/0,0,0,0,0,1,-10\n"),
            "test.cl:1:20: the CIRCLE radius must be positive");
}

TEST(ClReaderEvents, NonMotionStatementsAreRecordedWithTheirLine) {
  const auto p = read(
      "PARTNO  BRACKET, OP 20\n"
      "MACHIN/MILL,1\n"
      "TOOL PATH/FINISH_5AX,TOOL,BALL10\n"
      "TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000\n"
      "MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n"
      "SELECT/TOOL,3\n"
      "LOADTL/3\n"
      "LOAD/TOOL,3\n"
      "CUTTER/10,5\n"
      "spindl/rpm,12000,clw\n"
      "COOLNT/FLOOD\n"
      "PPRINT/Finish, 5-axis / ball end\n"
      "INSERT G64 P0.01\n"
      "CLEARP/ZAXIS,50\n"
      "PAINT/COLOR,186\n"
      "CUTCOM/OFF\n"
      "OPSTOP\n"
      "MULTAX/ON\n"
      "MULTAX\n"
      "END-OF-PATH\n"
      "COOLNT/OFF\n"
      "SPINDL/OFF\n"
      "END\n");
  const std::vector<std::string> expected = {
      "PARTNO BRACKET, OP 20",
      "MACHIN/MILL,1",
      "TOOL PATH/FINISH_5AX,TOOL,BALL10",
      "TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000",
      "MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000",
      "SELECT/TOOL,3",
      "LOADTL/3",
      "LOAD/TOOL,3",
      "CUTTER/10,5",
      "SPINDL/RPM,12000,CLW",
      "COOLNT/FLOOD",
      "PPRINT Finish, 5-axis / ball end",
      "INSERT G64 P0.01",
      "CLEARP/ZAXIS,50",
      "PAINT/COLOR,186",
      "CUTCOM/OFF",
      "OPSTOP",
      "END-OF-PATH",
      "COOLNT/OFF",
      "SPINDL/OFF",
  };
  ASSERT_EQ(p.events.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(p.events[i].what, expected[i]);
  EXPECT_EQ(p.events[0].line, 1);
  EXPECT_EQ(p.events[9].line, 10);
  EXPECT_EQ(p.events.back().line, 22);
  EXPECT_EQ(p.end_line, 23);
  EXPECT_TRUE(p.moves.empty());
}

TEST(ClReaderEnd, EndOrFiniStopsReading) {
  const auto p = read("RAPID\nGOTO/1,2,3\nEND\nGOTO/4,5,6\nNONSENSE/1\n");
  EXPECT_EQ(p.moves.size(), 1u);
  EXPECT_EQ(p.end_line, 3);
  EXPECT_EQ(read("RAPID\nGOTO/1,2,3\n\nFINI\n").end_line, 4);
}

TEST(ClReaderEnd, WithoutEndTheLastLine) {
  EXPECT_EQ(read("RAPID\nGOTO/1,2,3\n$$ done\n").end_line, 3);
  EXPECT_EQ(read("RAPID\nGOTO/1,2,3").end_line, 2);
}

TEST(ClReaderOpskip, StatementsBetweenOnAndOffFollowTheBlockDeleteSwitch) {
  const std::string text = "FEDRAT/100\nGOTO/1,0,0\nOPSKIP/ON\nGOTO/2,0,0\nOPSKIP/OFF\nGOTO/3,0,0\n";
  EXPECT_EQ(read(text).moves.size(), 2u);  // switch on (the default): skipped
  InterpretOptions keep;
  keep.block_delete = false;
  EXPECT_EQ(read(text, keep).moves.size(), 3u);
}

TEST(ClReaderErrors, UnknownStatement) {
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\n  GOBAK\n"), "test.cl:2:3: unknown statement 'GOBAK'");
  EXPECT_EQ(cl_reader_error_of("INDIRV/1,0,0\nTLON,GOFWD/(CIRCLE/0,0,0,5),ON,(LINE/0,0,0,1,1,0)\n"),
            "test.cl:2:1: 'TLON,GOFWD' is APT part-program motion (drive and check surfaces), not CL data: "
            "output the CAM program as CL records (GOTO, CIRCLE)");
  EXPECT_EQ(cl_reader_error_of("ROTATE/DRILL,10,FEDTO,0\n"), "test.cl:1:1: unknown statement 'ROTATE'");
  EXPECT_EQ(cl_reader_error_of("CYCLE/DRILL,10,FEDTO,0\n"), "test.cl:1:22: CYCLE gives the FEDTO twice");
  EXPECT_EQ(cl_reader_error_of("1.0,2.0,3.0\n"), "test.cl:1:1: unknown statement '1.0,2.0,3.0'");
}

TEST(ClReaderErrors, BadNumbersNameTheirColumn) {
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1.0, 2.0.1, 3\n"), "test.cl:2:11: bad number '2.0.1'");
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1.0,,3\n"), "test.cl:2:10: missing value");
  EXPECT_EQ(cl_reader_error_of("FEDRAT/fast\n"), "test.cl:1:8: unknown FEDRAT modifier 'fast'");
  EXPECT_EQ(cl_reader_error_of("FEDRAT/-5\n"), "test.cl:1:8: the feed rate must be positive");
  EXPECT_EQ(cl_reader_error_of("FEDRAT/MMPM\n"), "test.cl:1:1: FEDRAT without a feed value");
}

TEST(ClReaderErrors, ZeroToolAxis) {
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1,2,3, 0,0,0\n"),
            "test.cl:2:13: the axis vector (i,j,k) has zero length");
  EXPECT_EQ(cl_reader_error_of("TLAXIS/0,0,0\n"), "test.cl:1:8: the axis vector (i,j,k) has zero length");
}

TEST(ClReaderErrors, WrongValueCounts) {
  EXPECT_EQ(cl_reader_error_of("FEDRAT/100\nGOTO/1,2,3,4\n"),
            "test.cl:2:1: GOTO takes x,y,z or x,y,z,i,j,k (or several of them), got 4 values");
  EXPECT_EQ(cl_reader_error_of("GOTO/1,2\n"),
            "test.cl:1:1: GOTO takes x,y,z or x,y,z,i,j,k (or several of them), got 2 values");
  EXPECT_EQ(cl_reader_error_of("FROM/1,2,3,4,5\n"),
            "test.cl:1:1: FROM takes x,y,z or x,y,z,i,j,k (or several of them), got 5 values");
  EXPECT_EQ(cl_reader_error_of("FROM/1,2,3,4,5,6,7,8,9\n"),
            "test.cl:1:1: FROM takes one point (x,y,z or x,y,z,i,j,k)");
  EXPECT_EQ(cl_reader_error_of("MULTAX/ON\nFEDRAT/100\nGOTO/1,2,3,4,5,6,7,8,9\n"),
            "test.cl:3:1: GOTO under MULTAX/ON takes x,y,z,i,j,k per point, got 9 values");
  EXPECT_EQ(cl_reader_error_of("TLAXIS/0,1\n"), "test.cl:1:1: TLAXIS takes 3 values (i,j,k), got 2");
  EXPECT_EQ(cl_reader_error_of("RAPID/1\n"), "test.cl:1:7: RAPID takes no values");
}

TEST(ClReaderErrors, StateThatIsMissingOrNotSupported) {
  EXPECT_EQ(cl_reader_error_of("GOTO/1,2,3\n"), "test.cl:1:1: cutting move before any feed rate (FEDRAT)");
  EXPECT_EQ(cl_reader_error_of("CUTCOM/LEFT\n"),
            "test.cl:1:8: CUTCOM/LEFT needs the cutter's diameter (CUTTER/d or TLDATA)");
  EXPECT_EQ(cl_reader_error_of("UNITS/FEET\n"), "test.cl:1:7: UNITS takes MM or INCHES");
  EXPECT_EQ(cl_reader_error_of("SPINDL/SFM,300\n"),
            "test.cl:1:8: surface speed (SFM/SMM) is not supported: give the speed in RPM");
  EXPECT_EQ(cl_reader_error_of("SPINDL/1000,FAST\n"), "test.cl:1:13: unknown SPINDL modifier 'FAST'");
  EXPECT_EQ(cl_reader_error_of("DELAY/REV,5\n"), "test.cl:1:7: DELAY/REV needs a spindle speed (SPINDL/rpm)");
  EXPECT_EQ(cl_reader_error_of("MULTAX/MAYBE\n"), "test.cl:1:8: MULTAX takes ON or OFF");
}

TEST(ClReaderErrors, MessageNamesTheSource) {
  auto p = read_cl_data("BOGUS\n", "parts/op10.cls");
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().message, "parts/op10.cls:1:1: unknown statement 'BOGUS'");
}

TEST(ClReaderFile, NxStyleFinishingPath) {
  const auto p = read(
      "TOOL PATH/CONTOUR_5AX,TOOL,BALL_D10\n"
      "TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000\n"
      "MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n"
      "$$ centerline data\n"
      "PAINT/PATH\n"
      "PAINT/SPEED,10\n"
      "LOAD/TOOL,1\n"
      "SPINDL/RPM,8000.0000,CLW\n"
      "PAINT/COLOR,186\n"
      "RAPID\n"
      "GOTO/-40.0000,-30.0000,40.0000,0.0000000,0.0000000,1.0000000\n"
      "PAINT/COLOR,42\n"
      "FEDRAT/MMPM,300.0000\n"
      "GOTO/-40.0000,-30.0000,5.0000\n"
      "PAINT/COLOR,31\n"
      "FEDRAT/MMPM,1200.0000\n"
      "GOTO/-40.0000,-25.0000,5.2000,0.0000000,-0.0333148,0.9994449\n"
      "GOTO/-40.0000,-20.0000,5.3500,0.0000000,-0.0666297,0.9977778\n"
      "PAINT/COLOR,37\n"
      "RAPID\n"
      "GOTO/-40.0000,-20.0000,40.0000,0.0000000,0.0000000,1.0000000\n"
      "PAINT/SPEED,10\n"
      "PAINT/TOOL,NOMORE\n"
      "END-OF-PATH\n");
  ASSERT_EQ(p.moves.size(), 5u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::rapid);
  EXPECT_DOUBLE_EQ(p.moves[1].feed_mm_min, 300.0);
  EXPECT_DOUBLE_EQ(p.moves[2].feed_mm_min, 1200.0);
  EXPECT_NEAR(p.moves[3].tool_axis.norm(), 1.0, 1e-15);
  EXPECT_EQ(p.moves[4].kind, MoveKind::rapid);
  EXPECT_EQ(p.end_line, 24);
}

TEST(ClReaderFile, ShippedBallEndExampleStaysInTheBrief) {
  std::ifstream in(test::source_path("examples/programs/ball_end_5axis.cl"));
  ASSERT_TRUE(in) << "examples/programs/ball_end_5axis.cl is missing";
  std::stringstream buffer;
  buffer << in.rdbuf();
  const auto p = read(buffer.str());
  EXPECT_GE(p.moves.size(), 150u);
  EXPECT_GT(p.end_line, 0);
  double max_tilt_deg = 0.0;
  for (const CanonicalMove& move : p.moves) {
    EXPECT_LE(std::abs(move.end_mm.x()), 60.0) << "line " << move.line;
    EXPECT_LE(std::abs(move.end_mm.y()), 60.0) << "line " << move.line;
    EXPECT_LE(std::abs(move.end_mm.z()), 40.0) << "line " << move.line;
    max_tilt_deg =
        std::max(max_tilt_deg, std::acos(std::clamp(move.tool_axis.z(), -1.0, 1.0)) * 180.0 / M_PI);
  }
  EXPECT_GT(max_tilt_deg, 5.0);
  EXPECT_LE(max_tilt_deg, 15.0);
}

TEST(ClReaderFile, ManyStatementsKeepTheirLines) {
  std::string text = "FEDRAT/1000\n";
  constexpr int kPoints = 20000;
  text.reserve(kPoints * 48);
  for (int i = 0; i < kPoints; ++i) {
    text += "GOTO/" + std::to_string(i * 0.001) + ",0.0000,-1.5000,0.0000000,0.0000000,1.0000000\n";
  }
  const auto p = read(text);
  ASSERT_EQ(p.moves.size(), static_cast<std::size_t>(kPoints));
  EXPECT_EQ(p.moves.back().line, kPoints + 1);
  EXPECT_NEAR(p.moves.back().end_mm.x(), (kPoints - 1) * 0.001, 1e-9);
}

}  // namespace
}  // namespace pkm::program
