// CL CUTCOM/LEFT|RIGHT: the same compensated path as the G-code interpreter's G41/G42 for APT data (the part
// contour); centre-path dialects (NX, Pro/CLfile, SolidWorks CAM) not offset again; errors.
#include <gtest/gtest.h>

#include <string>

#include "program/part_program.hpp"

namespace pkm::program {
namespace cl_cutcom_test {

Result<CanonicalProgram> cutcom_cl(const std::string& text, ProgramFormat format = ProgramFormat::apt) {
  InterpretOptions options;
  options.format = format;
  return read_cl_data(text, "test.cl", options);
}

void cutcom_expect_same_path(const CanonicalProgram& cl, const CanonicalProgram& gcode) {
  ASSERT_EQ(cl.moves.size(), gcode.moves.size());
  for (std::size_t i = 0; i < cl.moves.size(); ++i) {
    const CanonicalMove& a = cl.moves[i];
    const CanonicalMove& b = gcode.moves[i];
    EXPECT_EQ(a.kind, b.kind) << "move " << i;
    EXPECT_LT((a.end_mm - b.end_mm).norm(), 1e-9)
        << "move " << i << ": " << a.end_mm.transpose() << " vs " << b.end_mm.transpose();
    if (a.kind == MoveKind::arc) {
      EXPECT_LT((a.center_mm - b.center_mm).norm(), 1e-9) << "move " << i;
      EXPECT_LT((a.normal - b.normal).norm(), 1e-12) << "move " << i;
    }
  }
}

// A closed contour with a convex corner, a concave one and an arc, entered from outside.
const char* const kCutcomContourCl =
    "CUTTER/6\n"
    "FEDRAT/MMPM,300\n"
    "GOTO/-10,-10,0\n"
    "CUTCOM/{SIDE},XYPLAN\n"
    "GOTO/0,0,0\n"
    "GOTO/40,0,0\n"
    "GOTO/40,40,0\n"
    "CIRCLE/20,40,0,0,0,1,20\n"
    "GOTO/0,40,0\n"
    "GOTO/10,20,0\n"
    "GOTO/0,0,0\n"
    "CUTCOM/OFF\n"
    "GOTO/-10,-10,0\n";

const char* const kCutcomContourGcode =
    "G21 G17 G90 F300\n"
    "G1 X-10 Y-10 Z0\n"
    "{G} D6\n"
    "G1 X0 Y0\n"
    "X40\n"
    "Y40\n"
    "G3 X0 Y40 I-20 J0\n"
    "G1 X10 Y20\n"
    "X0 Y0\n"
    "G40\n"
    "G1 X-10 Y-10\n"
    "M2\n";

std::string cutcom_fill(std::string text, const std::string& key, const std::string& value) {
  text.replace(text.find(key), key.size(), value);
  return text;
}

TEST(ClCutcom, AptContourIsCompensatedAsG41AndG42) {
  for (const auto& [side, g] : {std::pair<std::string, std::string>{"LEFT", "G41.1"}, {"RIGHT", "G42.1"}}) {
    SCOPED_TRACE(side);
    auto cl = cutcom_cl(cutcom_fill(kCutcomContourCl, "{SIDE}", side));
    auto gcode = interpret_gcode(cutcom_fill(kCutcomContourGcode, "{G}", g), "test.ngc");
    ASSERT_TRUE(cl) << cl.error().message;
    ASSERT_TRUE(gcode) << gcode.error().message;
    cutcom_expect_same_path(cl.value(), gcode.value());
    // The path really moved: the first side runs 3 mm off the contour.
    bool offset = false;
    for (const CanonicalMove& m : cl.value().moves) offset |= std::abs(std::abs(m.end_mm.y()) - 3.0) < 1e-9;
    EXPECT_TRUE(offset);
  }
}

TEST(ClCutcom, TheToolAxisAgainstThePlaneNormalMirrorsTheSides) {
  // Seen from below (tool axis -Z) the tool's left is the right seen from above.
  const std::string below = "TLAXIS/0,0,-1\n" + cutcom_fill(kCutcomContourCl, "{SIDE}", "LEFT");
  auto cl = cutcom_cl(below);
  auto gcode = interpret_gcode(cutcom_fill(kCutcomContourGcode, "{G}", "G42.1"), "test.ngc");
  ASSERT_TRUE(cl) << cl.error().message;
  ASSERT_TRUE(gcode) << gcode.error().message;
  cutcom_expect_same_path(cl.value(), gcode.value());
}

TEST(ClCutcom, CentrePathDialectsAreNotOffsetAgain) {
  const std::string text = cutcom_fill(kCutcomContourCl, "{SIDE}", "LEFT");
  for (const ProgramFormat format : {ProgramFormat::nx, ProgramFormat::creo, ProgramFormat::solidworks}) {
    auto plain = cutcom_cl(cutcom_fill(kCutcomContourCl, "CUTCOM/{SIDE},XYPLAN\n", ""), format);
    auto cl = cutcom_cl(text, format);
    ASSERT_TRUE(plain) << plain.error().message;
    ASSERT_TRUE(cl) << cl.error().message;
    cutcom_expect_same_path(cl.value(), plain.value());
    bool noted = false;
    for (const std::string& note : cl.value().notes)
      noted |= note.find("tool-centre path") != std::string::npos;
    EXPECT_TRUE(noted);
  }
  // Pro/CLfile names its geometry: anything but OUTPUT_ON_CENTER is the contour.
  auto profile = cutcom_cl("$$-> CUTCOM_GEOMETRY_TYPE / OUTPUT_ON_PROFILE\n" + text, ProgramFormat::creo);
  auto gcode = interpret_gcode(cutcom_fill(kCutcomContourGcode, "{G}", "G41.1"), "test.ngc");
  ASSERT_TRUE(profile) << profile.error().message;
  cutcom_expect_same_path(profile.value(), gcode.value());
}

TEST(ClCutcom, CamworksOnThenLeft) {
  auto cl = cutcom_cl(cutcom_fill(kCutcomContourCl, "CUTCOM/{SIDE},XYPLAN\n", "CUTCOM/ ON\nCUTCOM/ LEFT\n"));
  ASSERT_TRUE(cl) << cl.error().message;
  auto gcode = interpret_gcode(cutcom_fill(kCutcomContourGcode, "{G}", "G41.1"), "test.ngc");
  ASSERT_TRUE(gcode);
  // CUTCOM/ON is a line of its own: the same moves, one line later.
  cutcom_expect_same_path(cl.value(), gcode.value());
}

std::string cutcom_error_of(const std::string& text) {
  auto program = cutcom_cl(text);
  if (program) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  return program.error().message;
}

TEST(ClCutcom, Errors) {
  EXPECT_EQ(cutcom_error_of("FEDRAT/100\nCUTCOM/LEFT\n"),
            "test.cl:2:8: CUTCOM/LEFT needs the cutter's diameter (CUTTER/d or TLDATA)");
  EXPECT_EQ(cutcom_error_of("CUTTER/6\nCUTCOM/LEFT,SIDEWAYS\n"),
            "test.cl:2:13: unknown CUTCOM word 'SIDEWAYS'");
  EXPECT_EQ(cutcom_error_of("CUTTER/6\nCUTCOM/XYPLAN\n"), "test.cl:2:1: CUTCOM needs LEFT, RIGHT or OFF");
  EXPECT_EQ(cutcom_error_of("CUTTER/6\nTLAXIS/0,1,1\nCUTCOM/LEFT\n"),
            "test.cl:3:8: CUTCOM with a tool axis that is not a coordinate axis");
  EXPECT_EQ(cutcom_error_of("CUTTER/6\nCUTCOM/LEFT,YZPLAN\n"),
            "test.cl:2:8: CUTCOM in a plane the tool axis is not normal to");
  EXPECT_EQ(
      cutcom_error_of("CUTTER/6\nFEDRAT/100\nCUTCOM/LEFT\nGOTO/10,0,0\nGOTO/20,0,0,0,0.6,0.8\n"),
      "test.cl:5:1: a move with the tool axis tilted from the CUTCOM plane's normal under compensation");
  EXPECT_EQ(cutcom_error_of("CUTTER/6\nFEDRAT/100\nCUTCOM/LEFT\nRAPID\nGOTO/20,0,10\n"
                            "CYCLE/DRILL,8,MMPM,250,3\n"),
            "test.cl:6:1: CYCLE with cutter compensation on (CUTCOM/OFF first)");
}

}  // namespace cl_cutcom_test
}  // namespace pkm::program
