// CL dialects: the reader recognises the CAM system from the content, and reads each one's conventions (arc
// direction, six-value CIRCLE, TIMES helices, frames, annotations) as that system means them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "program/part_program.hpp"
#include "program/program_format.hpp"

namespace pkm::program {
namespace {

CanonicalProgram read_dialect(std::string_view text, ProgramFormat format = ProgramFormat::automatic,
                              bool transforms = true) {
  InterpretOptions options;
  options.format = format;
  options.apply_cl_transforms = transforms;
  auto program = read_cl_data(text, "test.cls", options);
  if (!program) {
    ADD_FAILURE() << program.error().message;
    return {};
  }
  return std::move(program.value());
}

std::string dialect_error_of(std::string_view text, ProgramFormat format = ProgramFormat::automatic) {
  InterpretOptions options;
  options.format = format;
  auto program = read_cl_data(text, "test.cls", options);
  if (program) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  return program.error().message;
}

void expect_vector_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol = 1e-9) {
  EXPECT_LT((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

bool has_note_containing(const CanonicalProgram& p, std::string_view text) {
  for (const std::string& note : p.notes)
    if (note.find(text) != std::string::npos) return true;
  return false;
}

TEST(ProgramFormatDetection, NamesTheCamSystemFromItsHeader) {
  EXPECT_EQ(detect_program_format("TOOL PATH/PLANAR,TOOL,MILL\nTLDATA/MILL,10,0,50,0,0\nGOTO/1,2,3\n"),
            ProgramFormat::nx);
  EXPECT_EQ(
      detect_program_format("$$*  Pro/CLfile  Version 8.0\n$$-> MFGNO / X\nPARTNO / X\nGOTO / 1, 2, 3\n"),
      ProgramFormat::creo);
  EXPECT_EQ(detect_program_format("$$ CATIA APT VERSION 1.0\n$$*CATIA0\nGOTO/1,2,3\n"), ProgramFormat::catia);
  EXPECT_EQ(detect_program_format("PARTNO/X\n$$ CAMWorks 2022\nGOTO/1,2,3\n"), ProgramFormat::solidworks);
  // SolidWorks CAM names itself nowhere; its own words do (UNIT, CSI_SET_…, TRNTYP, CAMWorks' OPFEATSTART).
  EXPECT_EQ(detect_program_format("UNIT/MM\nCSI_SET_FLUTE_LENGTH/20.\nGOTO/1,2,3\nGOTO/4,5,6\n"),
            ProgramFormat::solidworks);
  EXPECT_EQ(detect_program_format("OPFEATSTART/Drill1\nRAPID/\nGOTO/ 1,2,3\nOPFEATEND/Drill1\n"),
            ProgramFormat::solidworks);
  EXPECT_EQ(detect_program_format("UNITS/MM\nFEDRAT/100\nGOTO/1,2,3\nGOTO/4,5,6\nFINI\n"),
            ProgramFormat::apt);
  EXPECT_EQ(detect_program_format("units/mm\nfedrat/100\ngoto/1,2,3\nfini\n"), ProgramFormat::apt);
}

TEST(ProgramFormatDetection, GcodeIsNotClData) {
  EXPECT_EQ(detect_program_format("G21 G90\nG1 X1 Y2 F100\nM2\n"), ProgramFormat::gcode);
  EXPECT_EQ(detect_program_format("%\nO1000 (PART)\nN10 G0 X0\nn20 g1 x1 f100\n%\n"), ProgramFormat::gcode);
  EXPECT_EQ(detect_program_format("o<sub> sub\n#1 = 2\no<sub> endsub\nM2\n"), ProgramFormat::gcode);
  EXPECT_EQ(detect_program_format("(GOTO/1,2,3 in a comment)\nG0 X1\n"), ProgramFormat::gcode);
  EXPECT_EQ(detect_program_format(""), ProgramFormat::gcode);
}

TEST(ProgramFormatKeys, RoundTrip) {
  for (const ProgramFormat f :
       {ProgramFormat::automatic, ProgramFormat::gcode, ProgramFormat::apt, ProgramFormat::nx,
        ProgramFormat::creo, ProgramFormat::catia, ProgramFormat::solidworks}) {
    EXPECT_EQ(parse_program_format(program_format_key(f)), f);
  }
  EXPECT_EQ(parse_program_format("NX"), ProgramFormat::nx);
  EXPECT_FALSE(parse_program_format("mastercam").has_value());
}

// A quarter circle of radius 10 about the origin, entered tangentially from (10,-5) going +Y: counter-
// clockwise in the XY plane. NX writes its axis as (0,0,-1) (clockwise about it); the others as (0,0,1).
constexpr const char* kQuarterBody =
    "FROM/10,-5,0\nFEDRAT/MMPM,100\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,{},10\nGOTO/0,10,0\n";

std::string quarter(const char* sign) {
  std::string body = kQuarterBody;
  body.replace(body.find("{}"), 2, sign);
  return body;
}

TEST(ClDialectArcs, NxTurnsClockwiseAboutTheAxisOthersCounterClockwise) {
  const auto nx = read_dialect(quarter("-1"), ProgramFormat::nx);
  ASSERT_EQ(nx.moves.size(), 2u);
  expect_vector_near(nx.moves[1].normal, {0, 0, 1});  // canonical: counter-clockwise about +Z
  EXPECT_TRUE(nx.notes.empty());
  for (const ProgramFormat f : {ProgramFormat::apt, ProgramFormat::creo, ProgramFormat::solidworks}) {
    const auto p = read_dialect(quarter("1"), f);
    ASSERT_EQ(p.moves.size(), 2u);
    expect_vector_near(p.moves[1].normal, {0, 0, 1});
    EXPECT_TRUE(p.notes.empty()) << program_format_key(f);
  }
}

TEST(ClDialectArcs, AWrongConventionIsReportedWithTheLines) {
  const auto p = read_dialect(quarter("1"), ProgramFormat::nx);  // an APT file read as NX: reversed
  ASSERT_EQ(p.moves.size(), 2u);
  expect_vector_near(p.moves[1].normal, {0, 0, -1});
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_NE(p.notes[0].find("1 arc(s) start against the direction of the move before them (lines 5)"),
            std::string::npos)
      << p.notes[0];
  EXPECT_NE(p.notes[0].find("NX CLSF"), std::string::npos);
}

TEST(ClDialectArcs, ExplicitDirectionWordsWin) {
  for (const ProgramFormat f : {ProgramFormat::nx, ProgramFormat::apt}) {
    auto text = quarter("1");
    text.replace(text.find(",10\nGOTO/0,10"), 3, ",10,COUNTERCLOCKWISE");
    const auto ccw = read_dialect(text, f);
    expect_vector_near(ccw.moves[1].normal, {0, 0, 1});
    text = quarter("-1");
    text.replace(text.find(",10\nGOTO/0,10"), 3, ",10,CLOCKWISE");
    const auto cw = read_dialect(text, f);
    expect_vector_near(cw.moves[1].normal, {0, 0, 1});  // clockwise about -Z
  }
}

TEST(ClDialectArcs, SixValueCircleTakesTheRadiusFromTheStart) {
  const auto p = read_dialect("FEDRAT/100,MMPM\nGOTO/7,0,0\nCIRCLE/0,0,0,0,0,1.\nGOTO/0,7,0\n",
                              ProgramFormat::solidworks);
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[1].kind, MoveKind::arc);
  expect_vector_near(p.moves[1].center_mm, {0, 0, 0});
  EXPECT_NE(dialect_error_of("FEDRAT/100\nGOTO/0,0,0\nCIRCLE/0,0,0,0,0,1\nGOTO/1,0,0\n"), "");
}

// SolidWorks CAM writes the axis of the shorter arc: a 270° arc that continues the move before it is meant.
TEST(ClDialectArcs, SolidWorksLongArcsFollowTheTangent) {
  const std::string text =
      "FEDRAT/100,MMPM\nGOTO/-5,-10,0\nGOTO/0,-10,0\nCIRCLE/0,0,0,0,0,-1.\nGOTO/-10,0,0\n";
  // From (0,-10) moving +X, counter-clockwise about +Z to (-10,0) is 270°; the file states the 90° arc's
  // axis (clockwise about +Z = counter-clockwise about -Z).
  const auto p = read_dialect(text, ProgramFormat::solidworks);
  ASSERT_EQ(p.moves.size(), 3u);
  expect_vector_near(p.moves[2].normal, {0, 0, 1});
  EXPECT_TRUE(has_note_containing(p, "taken the long way round"));
  const auto literal = read_dialect(text, ProgramFormat::apt);  // APT: as written, and reported
  expect_vector_near(literal.moves[2].normal, {0, 0, -1});
  EXPECT_TRUE(has_note_containing(literal, "start against the direction"));
}

TEST(ClDialectArcs, TimesMakesHelixTurns) {
  const auto p = read_dialect(
      "TOOL PATH/HELIX,TOOL,MILL\nFEDRAT/MMPM,100\nGOTO/10,0,0\n"
      "CIRCLE/0,0,-6,0,0,-1,10,0.01,0.5,20,0,TIMES,3\nGOTO/10,0,-6\nEND-OF-PATH\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_EQ(p.moves[1].turns, 3);
  expect_vector_near(p.moves[1].normal, {0, 0, 1});  // NX: clockwise about -Z
  expect_vector_near(p.moves[1].center_mm, {0, 0, 0});
  expect_vector_near(p.moves[1].end_mm, {10, 0, -6});
}

TEST(ClDialectMotion, MultiPointGotoAndGohome) {
  const auto p =
      read_dialect("FROM/0,0,50\nFEDRAT/100\nGOTO/1,0,0,2,0,0,3,0,0\nRAPID\nGOTO/3,0,10\nGOHOME\n");
  ASSERT_EQ(p.moves.size(), 5u);
  expect_vector_near(p.moves[2].end_mm, {3, 0, 0});
  EXPECT_EQ(p.moves[3].kind, MoveKind::rapid);
  EXPECT_EQ(p.moves[4].kind, MoveKind::rapid);
  expect_vector_near(p.moves[4].end_mm, {0, 0, 50});
  const auto multax = read_dialect("MULTAX/ON\nFEDRAT/100\nGOTO/1,0,0,0,0,1,2,0,0,1,0,0\n");
  ASSERT_EQ(multax.moves.size(), 2u);
  expect_vector_near(multax.moves[1].tool_axis, {1, 0, 0});
  const auto nx_home = read_dialect("FEDRAT/MMPM,100\nGOTO/1,2,3\nGOHOME/650,-393,964\n", ProgramFormat::nx);
  expect_vector_near(nx_home.moves.back().end_mm, {650, -393, 964});
}

TEST(ClDialectUnits, UnitAndUnitsBothScale) {
  const auto p = read_dialect("UNIT/INCHES\nFEDRAT/10\nGOTO/1,0,0\nUNIT/MM\nGOTO/1,0,0\n");
  ASSERT_EQ(p.moves.size(), 2u);
  expect_vector_near(p.moves[0].end_mm, {25.4, 0, 0});
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 254.0);
  expect_vector_near(p.moves[1].end_mm, {1, 0, 0});
}

// MSYS: origin (100,0,0), X along +Y, Y along -X (a quarter turn about Z). A CL point (1,0,0) is at (100,1,0)
// of the part, a CL tool axis (1,0,0) is (0,1,0) there.
TEST(ClDialectFrames, MsysTurnsPointsAndAxesIntoThePartFrame) {
  const std::string text =
      "TOOL PATH/OP,TOOL,MILL\nMSYS/100,0,0,0,1,0,-1,0,0\nFEDRAT/MMPM,100\nGOTO/1,0,0,1,0,0\n"
      "CIRCLE/0,0,0,0,0,-1,1,0.01,0.5,10,0\nGOTO/0,1,0\nEND-OF-PATH\n";
  const auto p = read_dialect(text);
  ASSERT_EQ(p.moves.size(), 2u);
  expect_vector_near(p.moves[0].end_mm, {100, 1, 0});
  expect_vector_near(p.moves[0].tool_axis, {0, 1, 0});
  expect_vector_near(p.moves[1].end_mm, {99, 0, 0});
  expect_vector_near(p.moves[1].center_mm, {100, 0, 0});
  const auto kept = read_dialect(text, ProgramFormat::automatic, false);
  expect_vector_near(kept.moves[0].end_mm, {1, 0, 0});
  expect_vector_near(kept.moves[1].end_mm, {0, 1, 0});
}

TEST(ClDialectFrames, ProClfileCsysIsContinuedAndApplied) {
  const std::string text =
      "$$*  Pro/CLfile  Version 8.0\n$$-> FEATNO / 32\nUNITS / MM\n"
      "$$-> CSYS / 1.0, 0.0, 0.0, 5.0,  $\n      0.0, 1.0, 0.0, 6.0,  $\n      0.0, 0.0, 1.0, 7.0\n"
      "FEDRAT / 100.0, MMPM\nGOTO / 1.0, 2.0, 3.0\n$$-> END /\nGOTO / 2.0, 2.0, 3.0\nFINI\n";
  const auto p = read_dialect(text);
  EXPECT_EQ(p.format, "Pro/CLfile (Creo)");
  ASSERT_EQ(p.moves.size(), 2u);  // "$$-> END /" ends a feature, not the program
  expect_vector_near(p.moves[0].end_mm, {6, 8, 10});
  bool featno = false;
  for (const ProgramEvent& e : p.events) featno = featno || e.what == "FEATNO/32";
  EXPECT_TRUE(featno);
}

TEST(ClDialectFrames, SolidWorksCsysDescribesTheSetupOnly) {
  const auto p = read_dialect(
      "UNIT/MM\nTRNTYP/WORLD,0,0,0\nCSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0\nFEDRAT/100.,MMPM\nGOTO/"
      "1.,2.,3.,1.,0,0\n",
      ProgramFormat::solidworks);
  ASSERT_EQ(p.moves.size(), 1u);
  expect_vector_near(p.moves[0].end_mm, {1, 2, 3});
  expect_vector_near(p.moves[0].tool_axis, {1, 0, 0});
  EXPECT_NE(dialect_error_of("TRNTYP/WORLD,1,0,0\n"), "");
}

// CAMWorks turns the table A by 90° (radians), writes the points on the turned part, and turns back.
TEST(ClDialectFrames, RotablIsUndoneOnTheFixedPart) {
  const auto p = read_dialect(
      "$$ CAMWorks\nROTABL/ 1.570796,AAXIS,TABLE,CCLW\nFEDRAT/ MMPM,100\nGOTO/ 0,0,10\n"
      "ROTABL/ -1.570796,AAXIS,TABLE,CCLW\nGOTO/ 0,0,10\n");
  ASSERT_EQ(p.moves.size(), 2u);
  // The table turned the part +90° about X: a point (0,0,10) of the machine is (0,10,0) of the part.
  expect_vector_near(p.moves[0].end_mm, {0, 10, 0}, 1e-5);
  expect_vector_near(p.moves[0].tool_axis, {0, 1, 0}, 1e-5);
  expect_vector_near(p.moves[1].end_mm, {0, 0, 10}, 1e-9);
  const auto degrees = read_dialect("ROTABL/90,CAXIS\nFEDRAT/100\nGOTO/1,0,0\n", ProgramFormat::apt);
  expect_vector_near(degrees.moves[0].end_mm, {0, -1, 0}, 1e-12);
}

TEST(ClDialectEvents, CommentsAndAnnotationsAreKept) {
  const auto p = read_dialect(
      "$$ centerline data\nTOOL PATH/OP1,TOOL,MILL\nCSI_SET_FLUTE_LENGTH/20.\nOPFEATSTART/Pocket1\n"
      "MOVE_ATTRIB/LEADIN,END_ATTRIB\nSETUP/START,1\nBOX/0,0,0,10,10,10\nFEDRAT/MMPM,100\nGOTO/1,0,0\n"
      "OPFEATEND/Pocket1\n");
  EXPECT_EQ(p.moves.size(), 1u);
  std::vector<std::string> what;
  for (const ProgramEvent& e : p.events) what.push_back(e.what);
  const std::vector<std::string> expected = {"$$ centerline data",
                                             "TOOL PATH/OP1,TOOL,MILL",
                                             "CSI_SET_FLUTE_LENGTH/20.",
                                             "OPFEATSTART/POCKET1",
                                             "MOVE_ATTRIB/LEADIN,END_ATTRIB",
                                             "SETUP/START,1",
                                             "BOX/0,0,0,10,10,10",
                                             "OPFEATEND/POCKET1"};
  EXPECT_EQ(what, expected);
}

}  // namespace
}  // namespace pkm::program
