// The G-code interpreter: hand-checked moves, and every kind of error with its line and column.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include "program/gcode_arc.hpp"
#include "program/part_program.hpp"
#include "program/tool_table.hpp"

namespace {

using pkm::ErrorCode;
using pkm::program::CanonicalMove;
using pkm::program::CanonicalProgram;
using pkm::program::interpret_gcode;
using pkm::program::InterpretOptions;
using pkm::program::MoveKind;
using pkm::program::Plane;

CanonicalProgram gcode_interpreter_run(const std::string& text, const InterpretOptions& options = {}) {
  auto result = interpret_gcode(text, "t.ngc", options);
  if (!result) {
    ADD_FAILURE() << result.error().message;
    return {};
  }
  return std::move(result.value());
}

// The error message for `text`, which must fail.
std::string gcode_interpreter_error_of(const std::string& text, const InterpretOptions& options = {}) {
  auto result = interpret_gcode(text, "t.ngc", options);
  if (result) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  EXPECT_EQ(result.error().code, ErrorCode::bad_input);
  return result.error().message;
}

std::string gcode_interpreter_write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_gcode_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string tool_table() {
  static const std::string path = gcode_interpreter_write_temp("tools.tbl",
                                                               "T1 P1 Z25.0 D6 ;end mill\n"
                                                               "T2 P2 Z-10.5 D3 ;drill\n"
                                                               "\n"
                                                               "; comment line\n"
                                                               "T7 P3 Z100 X0 Y0.0\n");
  return path;
}

void expect_vec(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol = 1e-9) {
  EXPECT_LT((actual - expected).norm(), tol)
      << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

// Expects "t.ngc:LINE:COL: " at the start of `message` and `fragment` in it.
void expect_error_at(const std::string& message, int line, int column, const std::string& fragment) {
  const std::string prefix = "t.ngc:" + std::to_string(line) + ":" + std::to_string(column) + ": ";
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\n(expected prefix " << prefix << ")";
  EXPECT_NE(message.find(fragment), std::string::npos)
      << message << "\n(expected to contain: " << fragment << ")";
}

// ---------------------------------------------------------------------------------------------------------
// Moves

TEST(GcodeInterpreter, RapidsAndLinesInMillimetres) {
  const auto p = gcode_interpreter_run("G21 G90\nG0 X10 Y5 Z2\nF600\nG1 Z-1\nX40\nM2\n");
  ASSERT_EQ(p.moves.size(), 3u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::rapid);
  EXPECT_EQ(p.moves[0].line, 2);
  expect_vec(p.moves[0].end_mm, {10, 5, 2});
  EXPECT_EQ(p.moves[0].feed_mm_min, 0.0);
  EXPECT_EQ(p.moves[1].kind, MoveKind::line);
  expect_vec(p.moves[1].end_mm, {10, 5, -1});
  EXPECT_EQ(p.moves[1].feed_mm_min, 600.0);
  expect_vec(p.moves[2].end_mm, {40, 5, -1});  // modal G1
  EXPECT_EQ(p.moves[2].line, 5);
  EXPECT_EQ(p.end_line, 6);
  EXPECT_EQ(p.source, "t.ngc");
}

TEST(GcodeInterpreter, InchesAreConvertedToMillimetres) {
  const auto p =
      gcode_interpreter_run("G20\nG0 X1 Y2\nG1 Z-0.5 F10\nG2 X2 Y2 I0.5 J0\nG64 P0.001\nG1 X0\nM2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  expect_vec(p.moves[0].end_mm, {25.4, 50.8, 0});
  expect_vec(p.moves[1].end_mm, {25.4, 50.8, -12.7});
  EXPECT_DOUBLE_EQ(p.moves[1].feed_mm_min, 254.0);
  expect_vec(p.moves[2].center_mm, {38.1, 50.8, -12.7});
  EXPECT_NEAR(p.moves[3].path_tolerance_mm, 0.0254, 1e-12);
}

TEST(GcodeInterpreter, FeedKeepsItsSpeedAcrossAUnitSwitch) {
  const auto p = gcode_interpreter_run("G20 F10\nG1 X1\nG21\nG1 X30\nM2\n");
  ASSERT_EQ(p.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 254.0);
  EXPECT_DOUBLE_EQ(p.moves[1].feed_mm_min, 254.0);
}

TEST(GcodeInterpreter, ArcDirectionsAndNormalsInEveryPlane) {
  const auto p = gcode_interpreter_run(
      "G21 F100\n"
      "G17 G2 X10 Y10 I10 J0\n"  // from 0,0,0: centre (10,0), clockwise seen from +Z
      "G3 X20 Y0 I0 J-10\n"      // centre (10,0)
      "G18 G3 X30 Z10 I10 K0\n"  // XZ: centre x=30 z=0
      "G19 G2 Y10 Z20 J10 K0\n"  // YZ: centre y=10 z=10
      "M2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_EQ(p.moves[0].kind, MoveKind::arc);
  expect_vec(p.moves[0].center_mm, {10, 0, 0});
  expect_vec(p.moves[0].normal, {0, 0, -1});
  EXPECT_EQ(p.moves[0].plane, Plane::xy);
  expect_vec(p.moves[1].normal, {0, 0, 1});
  expect_vec(p.moves[2].center_mm, {30, 0, 0});
  expect_vec(p.moves[2].normal, {0, 1, 0});  // G3 in G18: counter-clockwise about +Y (Z × X)
  EXPECT_EQ(p.moves[2].plane, Plane::zx);
  expect_vec(p.moves[3].center_mm, {30, 10, 10});
  expect_vec(p.moves[3].normal, {-1, 0, 0});  // G2 in G19
  EXPECT_EQ(p.moves[3].plane, Plane::yz);
  for (const auto& m : p.moves) EXPECT_EQ(m.turns, 1);
}

TEST(GcodeInterpreter, QuarterArcSweepsNinetyDegrees) {
  const auto p = gcode_interpreter_run("G21 F100\nG0 X10\nG3 X0 Y10 I-10 J0\nG2 X10 Y0 I0 J-10\nM2\n");
  ASSERT_EQ(p.moves.size(), 3u);
  EXPECT_NEAR(pkm::program::gcode::arc_sweep_rad({10, 0, 0}, p.moves[1]), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(pkm::program::gcode::arc_sweep_rad({0, 10, 0}, p.moves[2]), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(pkm::program::gcode::arc_length_mm({0, 10, 0}, p.moves[2]), 5 * std::numbers::pi, 1e-12);
}

TEST(GcodeInterpreter, RadiusArcsPickTheShortOrTheLongArc) {
  const auto p = gcode_interpreter_run(
      "G21 F100\nG2 X10 Y10 R10\nG0 X0 Y0\nG2 X10 Y10 R-10\nG0 X0 Y0\nG3 X10 Y10 R10\nM2\n");
  ASSERT_EQ(p.moves.size(), 5u);
  expect_vec(p.moves[0].center_mm, {10, 0, 0});  // clockwise quarter from (0,0) to (10,10)
  expect_vec(p.moves[2].center_mm, {0, 10, 0});  // the three-quarter arc
  expect_vec(p.moves[4].center_mm, {0, 10, 0});  // counter-clockwise quarter
  EXPECT_NEAR(pkm::program::gcode::arc_sweep_rad({0, 0, 0}, p.moves[2]), 1.5 * std::numbers::pi, 1e-12);
}

TEST(GcodeInterpreter, RadiusArcSlightlyTooShortIsAHalfCircle) {
  const auto p = gcode_interpreter_run("G21 F100\nG2 X10 R4.999\nM2\n");
  ASSERT_EQ(p.moves.size(), 1u);
  expect_vec(p.moves[0].center_mm, {5, 0, 0});
}

TEST(GcodeInterpreter, FullCircleAndHelixWithTurns) {
  const auto p = gcode_interpreter_run("G21 F100\nG0 X5\nG3 I-5 J0\nG2 X5 Y0 Z-6 I-5 J0 P3\nM2\n");
  ASSERT_EQ(p.moves.size(), 3u);
  expect_vec(p.moves[1].end_mm, {5, 0, 0});
  expect_vec(p.moves[1].center_mm, {0, 0, 0});
  EXPECT_NEAR(pkm::program::gcode::arc_sweep_rad({5, 0, 0}, p.moves[1]), 2 * std::numbers::pi, 1e-12);
  expect_vec(p.moves[2].end_mm, {5, 0, -6});
  expect_vec(p.moves[2].center_mm, {0, 0, 0});  // at the start's height
  EXPECT_EQ(p.moves[2].turns, 3);
  EXPECT_NEAR(pkm::program::gcode::arc_sweep_rad({5, 0, 0}, p.moves[2]), 6 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(pkm::program::gcode::arc_length_mm({5, 0, 0}, p.moves[2]), std::hypot(30 * std::numbers::pi, 6),
              1e-9);
}

TEST(GcodeInterpreter, IncrementalMovesAndArcCentres) {
  const auto p = gcode_interpreter_run(
      "G21 G91 F100\nG1 X5 Y5\nX5 A10\nG90.1 G90 G2 X20 Y5 I15 J5\nG91.1 G91 G2 X5 Y-5 I0 J-5\nM2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  expect_vec(p.moves[0].end_mm, {5, 5, 0});
  expect_vec(p.moves[1].end_mm, {10, 5, 0});
  EXPECT_DOUBLE_EQ(p.moves[1].end_abc_deg.x(), 10.0);
  expect_vec(p.moves[2].center_mm, {15, 5, 0});  // absolute centre
  expect_vec(p.moves[3].center_mm, {20, 0, 0});  // incremental from (20, 5)
  expect_vec(p.moves[3].end_mm, {25, 0, 0});
}

TEST(GcodeInterpreter, StartPositionFromOptions) {
  InterpretOptions options;
  options.start_mm = {1, 2, 3};
  options.start_abc_deg = {4, 5, 6};
  const auto p = gcode_interpreter_run("G91 G1 X1 F100\nM2\n", options);
  ASSERT_EQ(p.moves.size(), 1u);
  expect_vec(p.moves[0].end_mm, {2, 2, 3});
  expect_vec(p.moves[0].end_abc_deg, {4, 5, 6});
  expect_vec(p.start_mm, {1, 2, 3});
  expect_vec(p.start_abc_deg, {4, 5, 6});
}

TEST(GcodeInterpreter, ToolLengthOffsetsShiftProgramZ) {
  InterpretOptions options;
  options.tool_table_path = tool_table();
  const auto p = gcode_interpreter_run(
      "G21 F100\nG0 Z1\nT1 M6\nG43\nG1 X5\nG43 H2\nG1 X6\nG49\nG1 X7\nG43 H7 Z50\nG43 H0\nG1 X8\nM2\n",
      options);
  ASSERT_EQ(p.moves.size(), 6u);
  // The tool tip stays put when the offset changes, so its program Z changes by the offset (as rs274).
  expect_vec(p.moves[1].end_mm, {5, 0, 1 - 25.0});
  EXPECT_DOUBLE_EQ(p.moves[1].tool_length_mm, 25.0);
  expect_vec(p.moves[2].end_mm, {6, 0, 1 + 10.5});
  EXPECT_DOUBLE_EQ(p.moves[2].tool_length_mm, -10.5);
  expect_vec(p.moves[3].end_mm, {7, 0, 1});
  EXPECT_DOUBLE_EQ(p.moves[3].tool_length_mm, 0.0);
  expect_vec(p.moves[4].end_mm, {7, 0, 50});
  EXPECT_DOUBLE_EQ(p.moves[4].tool_length_mm, 100.0);
  expect_vec(p.moves[5].end_mm, {8, 0, 50 + 100 - 25.0});
  EXPECT_DOUBLE_EQ(p.moves[5].tool_length_mm, 25.0);
}

TEST(GcodeInterpreter, InverseTimeFeeds) {
  const auto p = gcode_interpreter_run("G21 G93\nG1 X10 F20\nG1 A90 F2\nG0 X0\nG94 F300\nG1 X1\nM2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_TRUE(p.moves[0].inverse_time);
  EXPECT_DOUBLE_EQ(p.moves[0].inverse_time_per_min, 20.0);
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 200.0);  // the equivalent speed, as rs274 reports it
  EXPECT_TRUE(p.moves[1].inverse_time);
  EXPECT_DOUBLE_EQ(p.moves[1].inverse_time_per_min, 2.0);
  EXPECT_DOUBLE_EQ(p.moves[1].feed_mm_min, 0.0);  // rotary only: no mm/min equivalent
  EXPECT_FALSE(p.moves[2].inverse_time);
  EXPECT_FALSE(p.moves[3].inverse_time);
  EXPECT_DOUBLE_EQ(p.moves[3].feed_mm_min, 300.0);
}

TEST(GcodeInterpreter, InverseTimeFeedsIgnoreInches) {
  const auto p = gcode_interpreter_run("G20 G93\nG1 X1 F4\nM2\n");
  ASSERT_EQ(p.moves.size(), 1u);
  EXPECT_DOUBLE_EQ(p.moves[0].inverse_time_per_min, 4.0);
  EXPECT_DOUBLE_EQ(p.moves[0].feed_mm_min, 4 * 25.4);
}

TEST(GcodeInterpreter, DwellStaysInPlace) {
  const auto p = gcode_interpreter_run("G21 F100\nG1 X3 Y4\nG4 P1.5\nG4 P2 G1 X5\nM2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  EXPECT_EQ(p.moves[1].kind, MoveKind::dwell);
  EXPECT_DOUBLE_EQ(p.moves[1].dwell_s, 1.5);
  expect_vec(p.moves[1].end_mm, {3, 4, 0});
  EXPECT_EQ(p.moves[1].feed_mm_min, 0.0);
  EXPECT_EQ(p.moves[2].kind, MoveKind::dwell);  // the dwell comes before the move of its block
  EXPECT_EQ(p.moves[3].kind, MoveKind::line);
}

TEST(GcodeInterpreter, PathControlModes) {
  const auto p = gcode_interpreter_run(
      "G21 F100\nG1 X1\nG64 P0.05\nG1 X2\nG61\nG1 X3\nG61.1\nG1 X4\nG64\nG1 X5\nG64 P0 X6\nM2\n");
  ASSERT_EQ(p.moves.size(), 6u);
  EXPECT_EQ(p.moves[0].path_tolerance_mm, -1.0);
  EXPECT_FALSE(p.moves[0].exact_stop);
  EXPECT_DOUBLE_EQ(p.moves[1].path_tolerance_mm, 0.05);
  EXPECT_FALSE(p.moves[1].exact_stop);
  EXPECT_TRUE(p.moves[2].exact_stop);
  EXPECT_EQ(p.moves[2].path_tolerance_mm, -1.0);
  EXPECT_TRUE(p.moves[3].exact_stop);
  EXPECT_FALSE(p.moves[4].exact_stop);
  EXPECT_EQ(p.moves[4].path_tolerance_mm, -1.0);
  EXPECT_EQ(p.moves[5].path_tolerance_mm, -1.0);  // P0: no limit, as LinuxCNC
}

TEST(GcodeInterpreter, EventsAreRecordedWithTheirLines) {
  InterpretOptions options;
  options.tool_table_path = tool_table();
  const auto p =
      gcode_interpreter_run("G21\nT1 M6\nS12000 M3\nM8\nM7\nM9\nS500\nM4\nM5\nT2\nM6\nM30\n", options);
  ASSERT_EQ(p.events.size(), 10u);
  EXPECT_EQ(p.events[0].what, "M6 T1");
  EXPECT_EQ(p.events[0].line, 2);
  EXPECT_EQ(p.events[1].what, "M3 S12000");
  EXPECT_EQ(p.events[2].what, "M8");
  EXPECT_EQ(p.events[3].what, "M7");
  EXPECT_EQ(p.events[4].what, "M9");
  EXPECT_EQ(p.events[5].what, "S500");
  EXPECT_EQ(p.events[6].what, "M4 S500");
  EXPECT_EQ(p.events[7].what, "M5");
  EXPECT_EQ(p.events[8].what, "T2");
  EXPECT_EQ(p.events[9].what, "M6 T2");
  EXPECT_EQ(p.end_line, 12);
}

TEST(GcodeInterpreter, ProgramEndsAtM2M30OrPercentOrLastLine) {
  EXPECT_EQ(gcode_interpreter_run("G21 F100\nG1 X1\nM30\nG1 X2\n").moves.size(), 1u);
  EXPECT_EQ(gcode_interpreter_run("G21 F100\nG1 X1\nM30\nG1 X2\n").end_line, 3);
  const auto percent = gcode_interpreter_run("%\nG21 F100\nG1 X1\n%\nG1 X5\n");
  EXPECT_EQ(percent.moves.size(), 1u);
  EXPECT_EQ(percent.end_line, 4);
  const auto no_end = gcode_interpreter_run("G21 F100\nG1 X1\n(last)\n");
  EXPECT_EQ(no_end.moves.size(), 1u);
  EXPECT_EQ(no_end.end_line, 3);
}

TEST(GcodeInterpreter, CommentsCaseBlanksAndBlockNumbers) {
  const auto p = gcode_interpreter_run(
      "(header) ; with ( a stray paren\n"
      "N10 g21 (mm) f 300\n"
      "n20G01x1y2(no blanks)\n"
      "G 1 X 1 0 . 5 Y - 2\r\n"
      "\tG1 X+7 Y.5 ; trailing comment X99\n"
      "G01 X5. Y-.25\n"
      "m2\n");
  ASSERT_EQ(p.moves.size(), 4u);
  expect_vec(p.moves[0].end_mm, {1, 2, 0});
  expect_vec(p.moves[1].end_mm, {10.5, -2, 0});
  expect_vec(p.moves[2].end_mm, {7, 0.5, 0});
  expect_vec(p.moves[3].end_mm, {5, -0.25, 0});
  EXPECT_EQ(p.moves[3].line, 6);
}

TEST(GcodeInterpreter, ByteOrderMarkIsSkipped) {
  const auto p = gcode_interpreter_run("\xEF\xBB\xBFG21 F100 G1 X1\nM2\n");
  ASSERT_EQ(p.moves.size(), 1u);
  EXPECT_EQ(p.moves[0].line, 1);
}

TEST(GcodeInterpreter, BlockDeleteSwitch) {
  const std::string text = "G21 F100\n/G1 X5\n  / G1 Y5\nG1 Z1\nM2\n";
  EXPECT_EQ(gcode_interpreter_run(text).moves.size(), 1u);  // on by default
  InterpretOptions off;
  off.block_delete = false;
  EXPECT_EQ(gcode_interpreter_run(text, off).moves.size(), 3u);
}

TEST(GcodeInterpreter, MotionCodeWithoutAxesIsAZeroLengthMove) {
  // As rs274: an explicit G0/G1 with no axis words moves to where the tool is; arc data alone repeats G2/G3.
  const auto p = gcode_interpreter_run("G21 F100\nG0 X5\nG0\nG1 F200\nG2 X15 I5\nI-5\nF50\nM2\n");
  ASSERT_EQ(p.moves.size(), 5u);
  expect_vec(p.moves[1].end_mm, {5, 0, 0});
  EXPECT_EQ(p.moves[2].kind, MoveKind::line);
  EXPECT_EQ(p.moves[2].feed_mm_min, 200.0);
  EXPECT_EQ(p.moves[4].kind, MoveKind::arc);
  expect_vec(p.moves[4].center_mm, {10, 0, 0});
}

TEST(GcodeInterpreter, AcceptedNoOpModes) {
  const auto p = gcode_interpreter_run("G17 G40 G49 G80 G54 G90 G91.1 G94 G97 G21\nF10 G1 X1\nM2\n");
  EXPECT_EQ(p.moves.size(), 1u);
}

TEST(GcodeInterpreter, ArcWithinRs274ToleranceIsAccepted) {
  // End radius 10.02 vs 10: 0.02 mm < 0.02·√2 mm (rs274 accepts it too, tests/program/conformance/33_*).
  const auto p = gcode_interpreter_run("G21 F100\nG2 X20.02 I10\nM2\n");
  EXPECT_EQ(p.moves.size(), 1u);
}

TEST(GcodeInterpreter, HundredThousandLinesAreFast) {
  std::string text = "G21 G90 G17 F1200\nG0 X0 Y0 Z1\n";
  text.reserve(4'000'000);
  double y = 0.0;
  for (int i = 0; i < 100'000; ++i) {
    const double x = 0.01 * (i + 1);
    if (i % 10 == 9) {  // a half circle of radius 0.005 to the next x at the same y
      text.append("G2 X" + std::to_string(x) + " Y" + std::to_string(y) + " I0.005 J0\n");
    } else {
      y = std::sin(x);
      text.append("G1 X" + std::to_string(x) + " Y" + std::to_string(y) + " Z-1.5\n");
    }
  }
  text.append("M30\n");
  const auto begin = std::chrono::steady_clock::now();
  const auto result = interpret_gcode(text, "big.ngc");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->moves.size(), 100'001u);
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("interpreted 100000 lines in %.3f s\n", seconds);
  EXPECT_LT(seconds, 2.0);  // ~0.05 s in Release; generous for sanitizer builds
}

// ---------------------------------------------------------------------------------------------------------
// Errors: every one names the line and the column.

TEST(GcodeInterpreterErrors, MessageFormatNamesSourceLineColumn) {
  auto result = interpret_gcode("G21\n\n\n\n\n\n\n\n\n\n\nN12 G33 X1 K1\n", "pocket.ngc");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().message, "pocket.ngc:12:5: unsupported G-code G33 (spindle-synchronized motion)");
}

// Syntax errors read as rs274's, at the column of what broke the reading.
TEST(GcodeInterpreterErrors, BadNumbers) {
  expect_error_at(gcode_interpreter_error_of("G21\nG1 X1.2.3 F1\n"), 2, 5, "bad number format");
  expect_error_at(gcode_interpreter_error_of("G1 Y. F1\n"), 1, 5, "bad number format");
  expect_error_at(gcode_interpreter_error_of("G1 X1e3 F1\n"), 1, 6, "E word is not supported");
  expect_error_at(gcode_interpreter_error_of("G1.25 X1\n"), 1, 1, "bad G-code number");
  expect_error_at(gcode_interpreter_error_of("M6.5\n"), 1, 1, "bad M-code number");
  expect_error_at(gcode_interpreter_error_of("G21\nG1000\n"), 2, 1, "bad G-code number");
}

TEST(GcodeInterpreterErrors, LetterWithoutNumber) {
  // A letter reads an expression: `X F10` reads F as the start of one, as rs274 does.
  expect_error_at(gcode_interpreter_error_of("G21\nG1 X F10\n"), 2, 6, "Unknown word starting with f");
  expect_error_at(gcode_interpreter_error_of("G1 X1 G\n"), 1, 8, "No characters found in reading real value");
}

TEST(GcodeInterpreterErrors, CommentsAndCharacters) {
  expect_error_at(gcode_interpreter_error_of("G21 (a (b) c)\n"), 1, 8, "Nested comment found");
  expect_error_at(gcode_interpreter_error_of("G21\nG0 X1 (open\n"), 2, 7, "Unclosed comment found");
  expect_error_at(gcode_interpreter_error_of("G0 X1 %\n"), 1, 7, "Bad character '%' used");
  // A control byte is named in octal, never sent to the terminal as it is.
  expect_error_at(gcode_interpreter_error_of(std::string("G0 X1 \x01\n")), 1, 7,
                  "Bad character '\\001' used");
  expect_error_at(gcode_interpreter_error_of("G21\n% junk\n"), 2, 1, "Bad character '%' used");
}

TEST(GcodeInterpreterErrors, ParametersExpressionsAndOWords) {
  expect_error_at(gcode_interpreter_error_of("G0 X[1/0]\n"), 1, 7, "Attempt to divide by zero");
  expect_error_at(gcode_interpreter_error_of("G0 X#<nothing>\n"), 1, 5,
                  "Named parameter #<nothing> not defined");
  expect_error_at(gcode_interpreter_error_of("G0 X[SQRT[-1]]\n"), 1, 6, "Negative argument to sqrt");
  expect_error_at(gcode_interpreter_error_of("G0 X[ACOS[2]]\n"), 1, 6, "Argument to acos out of range");
  expect_error_at(gcode_interpreter_error_of("#6000=1\n"), 1, 1, "Parameter number out of range");
  expect_error_at(gcode_interpreter_error_of("G21\no100 endwhile\n"), 2, 1, "'o100 endwhile'");
  expect_error_at(gcode_interpreter_error_of("o1 sub\no1 call\no1 endsub\no1 call\n"), 2, 1,
                  "Too many subroutine levels");
  // A program that loops for ever is refused at the line that crossed the bound, not left to hang.
  InterpretOptions bounded;
  bounded.max_blocks = 1000;
  expect_error_at(gcode_interpreter_error_of("G21\no1 while [1]\nG0 X1\no1 endwhile\n", bounded), 2, 1,
                  "more than 1000 blocks executed");
}

TEST(GcodeInterpreterErrors, BlockNumberMustOpenTheBlock) {
  expect_error_at(gcode_interpreter_error_of("G1 N5 X1\n"), 1, 4, "Bad character 'n' used");
}

TEST(GcodeInterpreterErrors, UnknownAndUnsupportedCodes) {
  expect_error_at(gcode_interpreter_error_of("G21\nG12 X1\n"), 2, 1, "unknown G-code G12");
  expect_error_at(gcode_interpreter_error_of("G5.3\n"), 1, 1, "unsupported G-code G5.3 (spline");
  expect_error_at(gcode_interpreter_error_of("G21 G7\n"), 1, 5,
                  "unsupported G-code G7 (lathe diameter mode)");
  expect_error_at(gcode_interpreter_error_of("G76 X1\n"), 1, 1, "lathe tapping or threading cycle");
  expect_error_at(gcode_interpreter_error_of("G17.1\n"), 1, 1, "UVW plane");
  expect_error_at(gcode_interpreter_error_of("M250\n"), 1, 1, "unknown M-code M250");
  expect_error_at(gcode_interpreter_error_of("M98 P100\n"), 1, 1, "subprogram call");
}

TEST(GcodeInterpreterErrors, UnsupportedLetters) {
  expect_error_at(gcode_interpreter_error_of("G0 U1\n"), 1, 4, "U axis is not supported");
  expect_error_at(gcode_interpreter_error_of("G0 X1 W1\n"), 1, 7, "W axis is not supported");
  expect_error_at(gcode_interpreter_error_of("G0 X1 V1\n"), 1, 7, "V axis is not supported");
  // Words that only some codes use need one of them in the block.
  expect_error_at(gcode_interpreter_error_of("G1 Q1 X1 F1\n"), 1, 4, "Q word with no canned cycle");
  expect_error_at(gcode_interpreter_error_of("G1 X1 D3 F1\n"), 1, 7, "D word without G41");
  expect_error_at(gcode_interpreter_error_of("G1 X1 L3 F1\n"), 1, 7, "L word with no G10");
  expect_error_at(gcode_interpreter_error_of("G64 P0.1 Q0.1\n"), 1, 10, "Q word with no canned cycle");
}

TEST(GcodeInterpreterErrors, TwoCodesFromOneModalGroup) {
  expect_error_at(gcode_interpreter_error_of("G21\nG0 G1 X5\n"), 2, 4,
                  "G0 and G1 in one block belong to the same modal group");
  expect_error_at(gcode_interpreter_error_of("G20 G21\n"), 1, 5, "same modal group");
  expect_error_at(gcode_interpreter_error_of("G90 G91.1 G91\n"), 1, 11, "G90 and G91");
  expect_error_at(gcode_interpreter_error_of("M3 M4 S100\n"), 1, 4, "M3 and M4");
  expect_error_at(gcode_interpreter_error_of("M7 M8\n"), 1, 4, "M7 and M8");
  expect_error_at(gcode_interpreter_error_of("G61 G64\n"), 1, 5, "same modal group");
}

TEST(GcodeInterpreterErrors, RepeatedWord) {
  expect_error_at(gcode_interpreter_error_of("G0 X1 X2\n"), 1, 7, "two X words in one block");
  expect_error_at(gcode_interpreter_error_of("G1 F1 X1 F2\n"), 1, 10, "two F words");
}

TEST(GcodeInterpreterErrors, WordsNothingUses) {
  expect_error_at(gcode_interpreter_error_of("G21\nX5\n"), 2, 1, "axis words without a motion mode");
  expect_error_at(gcode_interpreter_error_of("G80 Y5\n"), 1, 5, "axis words with G80");
  expect_error_at(gcode_interpreter_error_of("G4 P1 X1\n"), 1, 7, "axis words without a motion mode");
  expect_error_at(gcode_interpreter_error_of("G1 X1 I1 F1\n"), 1, 7, "I word with no G2 or G3");
  expect_error_at(gcode_interpreter_error_of("G1 X1 F1 R2\n"), 1, 10, "R word with no G2 or G3");
  expect_error_at(gcode_interpreter_error_of("G1 X10 P2 F1\n"), 1, 8, "P word with no G2, G3, G4 or G64");
  expect_error_at(gcode_interpreter_error_of("F1 G2 X10 I5\nP2\n"), 2, 1, "P word with no G2, G3, G4 or G64");
  expect_error_at(gcode_interpreter_error_of("F1 G4 P1 G2 X10 I5\n"), 1, 7,
                  "P word claimed by more than one");
  expect_error_at(gcode_interpreter_error_of("H1\n"), 1, 1, "H word without G43");
  expect_error_at(gcode_interpreter_error_of("G49 H1\n"), 1, 5, "H word without G43");
}

TEST(GcodeInterpreterErrors, DwellNeedsPositiveP) {
  expect_error_at(gcode_interpreter_error_of("G21\nG4\n"), 2, 1, "G4 without a P word");
  expect_error_at(gcode_interpreter_error_of("G4 P-1\n"), 1, 4, "negative dwell time");
}

TEST(GcodeInterpreterErrors, NegativeOrNonIntegerValues) {
  expect_error_at(gcode_interpreter_error_of("G21 F-100\n"), 1, 5, "negative feed rate");
  expect_error_at(gcode_interpreter_error_of("S-5 M3\n"), 1, 1, "negative spindle speed");
  expect_error_at(gcode_interpreter_error_of("T1.5 M6\n"), 1, 1, "T must be a whole number");
  expect_error_at(gcode_interpreter_error_of("T-1\n"), 1, 1, "T must be a whole number");
  expect_error_at(gcode_interpreter_error_of("G21\nT12345678901\n"), 2, 1,
                  "T must be a whole number from 0 to 1000000");
  expect_error_at(gcode_interpreter_error_of("F1 G2 X10 I5 P1e9\n"), 1, 16, "E word");
  expect_error_at(gcode_interpreter_error_of("F1 G2 X10 I5 P1000000000\n"), 1, 14,
                  "P (turns) must be a whole number from 1");
  expect_error_at(gcode_interpreter_error_of("G43 H1.5\n"), 1, 5, "H must be a whole number");
  expect_error_at(gcode_interpreter_error_of("G64 P-0.1\n"), 1, 5, "negative G64 tolerance");
}

TEST(GcodeInterpreterErrors, FeedMissing) {
  expect_error_at(gcode_interpreter_error_of("G21\nG1 X1\n"), 2, 1, "G1 with no feed rate programmed (F)");
  expect_error_at(gcode_interpreter_error_of("G1 X1 F0\n"), 1, 7, "G1 with no feed rate");
  expect_error_at(gcode_interpreter_error_of("G0 X1\nG2 X3 I1\n"), 2, 1, "G2 with no feed rate");
  // G94 clears the feed, as in rs274.
  expect_error_at(gcode_interpreter_error_of("F100\nG94 G1 X1\n"), 2, 5, "G1 with no feed rate");
  expect_error_at(gcode_interpreter_error_of("G93\nG1 X1\n"), 2, 1,
                  "inverse-time mode (G93) needs an F word");
  expect_error_at(gcode_interpreter_error_of("G1 X1 F10\n  Y2 G93\n"), 2, 3,
                  "G1 in inverse-time mode (G93) needs an F word");
  expect_error_at(gcode_interpreter_error_of("G0 X1\n  G1 Y2\n"), 2, 3, "G1 with no feed rate");
  expect_error_at(gcode_interpreter_error_of("G93 G1 X1 F10\nX2\n"), 2, 1, "needs an F word");
  expect_error_at(gcode_interpreter_error_of("G93 G1 X1 F0\n"), 1, 11,
                  "inverse-time F must be greater than 0");
}

TEST(GcodeInterpreterErrors, ArcData) {
  expect_error_at(gcode_interpreter_error_of("G21 F100\nG2 X1\n"), 2, 1, "G2 with no I, J, K or R");
  expect_error_at(gcode_interpreter_error_of("F100 G3 X1 Y1\n"), 1, 6, "G3 with no I, J, K or R");
  expect_error_at(gcode_interpreter_error_of("F100 G2 X1 R1 I1\n"), 1, 12, "R and I/J/K in one arc");
  expect_error_at(gcode_interpreter_error_of("F100 G17 G2 X10 I5 K1\n"), 1, 20, "K word in a G17 (XY) arc");
  expect_error_at(gcode_interpreter_error_of("F100 G18 G2 X10 I5 J1\n"), 1, 20, "J word in a G18 (XZ) arc");
  expect_error_at(gcode_interpreter_error_of("F100 G19 G2 Y10 I5 J5\n"), 1, 17, "I word in a G19 (YZ) arc");
  expect_error_at(gcode_interpreter_error_of("F100 G90.1 G2 X10 Y0 I5\n"), 1, 22,
                  "J word missing: absolute arc centres");
}

TEST(GcodeInterpreterErrors, ArcGeometry) {
  // End off the circle: radius 10 at the start, 10.15 at the end (> 0.1 % and > 0.028 mm).
  expect_error_at(gcode_interpreter_error_of("G21 F100\nG2 X20.15 I10 J0\n"), 2, 11,
                  "arc end is not on the circle");
  // The same in inches: 0.003 inch off (> 0.002·√2 inch).
  expect_error_at(gcode_interpreter_error_of("G20 F10\nG2 X2.003 I1\n"), 2, 11,
                  "arc end is not on the circle");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X10 I0 J0\n"), 2, 8,
                  "zero-radius arc: the centre is the start point");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X10 I10 J0\n"), 2, 8,
                  "zero-radius arc: the centre is the end point");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X0 Y0 R5\n"), 2, 10,
                  "R arc with its end point at the start point");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X10 R4.99\n"), 2, 8,
                  "too small to reach the end point");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X10 R0\n"), 2, 8, "too small");
  expect_error_at(gcode_interpreter_error_of("F100\nG2 X10 I5 P0\n"), 2, 11,
                  "P (turns) must be a whole number from 1");
  expect_error_at(gcode_interpreter_error_of("F100\nG3 X10 I5 P1.5\n"), 2, 11,
                  "P (turns) must be a whole number from 1");
}

TEST(GcodeInterpreterErrors, ToolLengthWithoutATableIsZeroWithANote) {
  // As rs274 with no tool table: tools have zero length; the summary says so once.
  const auto program = interpret_gcode("G43 H1\nG1 Z1 F100\nG43 H2\nM2\n", "t.ngc");
  ASSERT_TRUE(program.ok()) << program.error().message;
  EXPECT_EQ(program->moves.at(0).tool_length_mm, 0.0);
  ASSERT_EQ(program->notes.size(), 1u);
  EXPECT_NE(program->notes[0].find("t.ngc:1: G43 for tool 1 without a tool table"), std::string::npos);
}

TEST(GcodeInterpreterErrors, ToolLengthNeedsTheToolInTheTable) {
  InterpretOptions options;
  options.tool_table_path = tool_table();
  expect_error_at(gcode_interpreter_error_of("G21\nG43 H5\n", options), 2, 5,
                  "tool 5 is not in the tool table");
  expect_error_at(gcode_interpreter_error_of("T9 M6\n", options), 1, 1, "tool T9 is not in the tool table");
}

// ---------------------------------------------------------------------------------------------------------
// Tool tables and files

TEST(GcodeToolTable, ParsesLinuxCncFormat) {
  auto table =
      pkm::program::parse_tool_table("T1 P1 Z25.0 D6 ;comment\n;only a comment\n\nT2 P5 Z-1.5\n", "t.tbl");
  ASSERT_TRUE(table.ok()) << table.error().message;
  ASSERT_EQ(table->entries().size(), 2u);
  ASSERT_NE(table->find(1), nullptr);
  EXPECT_DOUBLE_EQ(table->find(1)->length_mm, 25.0);
  EXPECT_DOUBLE_EQ(table->find(1)->diameter_mm, 6.0);
  EXPECT_EQ(table->find(2)->pocket, 5);
  EXPECT_EQ(table->find(3), nullptr);
}

TEST(GcodeToolTable, ErrorsNameLineAndColumn) {
  auto sideways = pkm::program::parse_tool_table("T1 P1 Z25\nT2 P2 X1 Z3\n", "t.tbl");
  ASSERT_FALSE(sideways.ok());
  EXPECT_EQ(sideways.error().message.rfind("t.tbl:2:7: ", 0), 0u) << sideways.error().message;
  auto no_tool = pkm::program::parse_tool_table("P1 Z25\n", "t.tbl");
  ASSERT_FALSE(no_tool.ok());
  EXPECT_EQ(no_tool.error().message.rfind("t.tbl:1:1: ", 0), 0u) << no_tool.error().message;
  auto twice = pkm::program::parse_tool_table("T1 Z1\nT1 Z2\n", "t.tbl");
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.error().message.find("t.tbl:2:1: tool T1 defined again"), std::string::npos);
  auto bad = pkm::program::parse_tool_table("T1 Z1.2.3\n", "t.tbl");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message.rfind("t.tbl:1:4: ", 0), 0u) << bad.error().message;
  auto marker = pkm::program::parse_tool_table("T1 Z1\n%\n", "t.tbl");
  ASSERT_FALSE(marker.ok());
  EXPECT_EQ(marker.error().message.rfind("t.tbl:2:1: not a tool table line", 0), 0u)
      << marker.error().message;
  auto huge = pkm::program::parse_tool_table("T1e3 Z1\n", "t.tbl");
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().message.rfind("t.tbl:1:3: ", 0), 0u) << huge.error().message;
  auto letter = pkm::program::parse_tool_table("T1 K1\n", "t.tbl");
  ASSERT_FALSE(letter.ok());
  EXPECT_EQ(letter.error().message.rfind("t.tbl:1:4: ", 0), 0u) << letter.error().message;
}

TEST(GcodeToolTable, MissingTableFileIsAnIoError) {
  InterpretOptions options;
  options.tool_table_path = "/nonexistent/pkm/tools.tbl";
  auto result = interpret_gcode("G21\n", "t.ngc", options);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::io);
  EXPECT_NE(result.error().message.find("/nonexistent/pkm/tools.tbl"), std::string::npos);
}

TEST(GcodeLoadPartProgram, ReadsGcodeFilesAndNamesThem) {
  const std::string path = gcode_interpreter_write_temp("load.ngc", "G21 F100\nG1 X1\nG1 X1.2.3\n");
  auto result = pkm::program::load_part_program(path);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().message.rfind(path + ":3:5: ", 0), 0u) << result.error().message;
  const std::string good = gcode_interpreter_write_temp("good.NGC", "G21 F100\nG1 X1\nM2\n");
  auto ok = pkm::program::load_part_program(good);
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_EQ(ok->moves.size(), 1u);
  EXPECT_EQ(ok->source, good);
}

TEST(GcodeLoadPartProgram, UnreadableFileIsAnIoErrorWithThePath) {
  auto result = pkm::program::load_part_program("/nonexistent/pkm/part.ngc");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::io);
  EXPECT_NE(result.error().message.find("/nonexistent/pkm/part.ngc"), std::string::npos);
}

TEST(GcodeLoadPartProgram, ClExtensionsGoToTheClReader) {
  // Not G-code: the CL reader takes .cl/.cls/.apt files, so a G-code error message must not appear.
  const std::string path = gcode_interpreter_write_temp("prog.cls", "G1 X1.2.3\n");
  auto result = pkm::program::load_part_program(path);
  if (!result.ok()) {
    EXPECT_EQ(result.error().message.find("bad number 'X1.2.3'"), std::string::npos);
  }
}

// The moves of canned cycles count against max_blocks: an L or a tiny Q makes one block expand to millions
// of moves, which the count of blocks alone would not bound (found by fuzz/fuzz_gcode).
TEST(GcodeInterpreterErrors, CycleMovesCountAgainstMaxBlocks) {
  InterpretOptions options;
  options.max_blocks = 1000;
  const std::string block = "G81 X1 R2 Z-2 L50 F100\n";  // 50 holes of 4 moves
  EXPECT_EQ(gcode_interpreter_run("G0 Z10\n" + block + block, options).moves.size(), 401u);
  expect_error_at(gcode_interpreter_error_of("G0 Z10\n" + block + block + block, options), 4, 15,
                  "50 holes in one cycle block: more than the 600 moves left to it");
}

// #5220 may hold anything a program writes there; one that names no coordinate system is G54, for G10 P0
// as for the frame (converting 1e30 to int was undefined: found by fuzz/fuzz_gcode's UBSan).
TEST(GcodeInterpreter, AnActiveSystemParameterOutOfRangeIsG54) {
  const CanonicalProgram p = gcode_interpreter_run("#5220=[10**30]\nG10 L2 P0 X5\nG0 X1\n");
  ASSERT_EQ(p.moves.size(), 1u);
  expect_vec(p.moves[0].end_mm, Eigen::Vector3d(6.0, 0.0, 0.0));
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// Parameter files (LinuxCNC's .var): offsets read at the start, written back at the end when asked.

TEST(GcodeParameterFile, OffsetsComeFromTheFileAndGoBackToIt) {
  const std::string var =
      gcode_interpreter_write_temp("offsets.var", "5161\t1.0\n5220\t1\n5221\t10.0\n5222\t20.0\n5223\t-5.0\n");
  InterpretOptions options;
  options.parameter_file = var;
  options.write_parameter_file = true;
  // The tool starts at the work frame's zero, which the program sees at (-10, -20, 5) through G54.
  const auto program =
      interpret_gcode("G21 G90\nG0 X1 Y2 Z3\nG10 L2 P1 X4\nG1 X0 F100\nG0 Y0\nG28.1\nM2\n", "t.ngc", options);
  ASSERT_TRUE(program.ok()) << program.error().message;
  ASSERT_EQ(program->moves.size(), 3u);
  EXPECT_TRUE(program->moves[0].end_mm.isApprox(Eigen::Vector3d(11.0, 22.0, -2.0)))
      << program->moves[0].end_mm;
  // G10 L2 moves G54 itself: the tool stays, its program X changes, and X0 is now at work X 4.
  EXPECT_NEAR(program->moves[1].end_mm.x(), 4.0, 1e-12);
  const auto& frame = program->frames.at(static_cast<std::size_t>(program->moves[1].frame));
  EXPECT_NEAR(frame.g5x_mm.x(), 4.0, 1e-12);
  EXPECT_NEAR(pkm::program::program_coordinates(*program, program->moves[1]).end_mm.x(), 0.0, 1e-12);
  // The file now holds the new offset and the G28 position stored by G28.1 (machine coordinates, mm).
  std::ifstream in(var);
  std::map<int, double> written;
  int number = 0;
  double value = 0.0;
  while (in >> number >> value) written[number] = value;
  EXPECT_NEAR(written.at(5221), 4.0, 1e-9);
  EXPECT_NEAR(written.at(5222), 20.0, 1e-9);
  EXPECT_NEAR(written.at(5161), 4.0, 1e-9);
  EXPECT_NEAR(written.at(5162), 20.0, 1e-9);
}

TEST(GcodeParameterFile, OffsetsStayInMillimetresInAnInchProgram) {
  // As LinuxCNC: parameters hold the machine's units (mm), whatever G20 says; #5420 is in program units.
  const auto program = interpret_gcode(
      "G20 G90\nG10 L2 P1 X1\nG54 G0 X0\n#1 = #5221\n#2 = #5420\nG0 Y[#1 / 100] Z#2\nM2\n", "t.ngc");
  ASSERT_TRUE(program.ok()) << program.error().message;
  const auto numbers = pkm::program::program_coordinates(*program, program->moves.back());
  EXPECT_NEAR(numbers.end_mm.y(), 25.4 / 100.0 * 25.4, 1e-9);  // #5221 = 25.4 (mm), read as inches
  EXPECT_NEAR(numbers.end_mm.z(), 0.0, 1e-12);                 // #5420 = X in program units = 0
}
