// The G-code writer: every conformance program read, written and read again gives the same moves (those
// with tool length offsets give the "not supported" error instead); events, feeds, options and the errors.
#include "program/gcode_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "program/part_program.hpp"
#include "source_paths.hpp"

namespace {

using pkm::ErrorCode;
using pkm::program::CanonicalMove;
using pkm::program::CanonicalProgram;
using pkm::program::GcodeWriteOptions;
using pkm::program::interpret_gcode;
using pkm::program::InterpretOptions;
using pkm::program::MoveKind;
using pkm::program::OrientationSource;
using pkm::program::Plane;
using pkm::program::ProgramEvent;
using pkm::program::write_gcode;

namespace fs = std::filesystem;

fs::path gcode_writer_conformance_dir() {
  return pkm::test::source_path("tests/program/conformance");
}

InterpretOptions with_tool_table() {
  InterpretOptions options;
  options.tool_table_path = (gcode_writer_conformance_dir() / "tools.tbl").string();
  return options;
}

std::vector<fs::path> gcode_writer_conformance_programs() {
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(gcode_writer_conformance_dir()))
    if (entry.path().extension() == ".ngc") paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  return paths;
}

CanonicalProgram interpret(const std::string& text) {
  auto result = interpret_gcode(text, "t.ngc", with_tool_table());
  if (!result) {
    ADD_FAILURE() << result.error().message;
    return {};
  }
  return std::move(result.value());
}

std::string written(const CanonicalProgram& program, const GcodeWriteOptions& options = {}) {
  auto text = write_gcode(program, options);
  if (!text) {
    ADD_FAILURE() << text.error().message;
    return {};
  }
  return std::move(text.value());
}

// How many moves come before the event: its place among the moves, which line numbers do not keep.
std::size_t moves_before(const CanonicalProgram& program, const ProgramEvent& event) {
  return static_cast<std::size_t>(std::count_if(program.moves.begin(), program.moves.end(),
                                                [&](const CanonicalMove& m) { return m.line < event.line; }));
}

// Same moves and events; lengths and angles to `tolerance` (mm, degrees), feeds relative to it.
void expect_same_program(const CanonicalProgram& expected, const CanonicalProgram& actual, double tolerance,
                         const std::string& name) {
  ASSERT_EQ(expected.moves.size(), actual.moves.size()) << name;
  for (std::size_t i = 0; i < expected.moves.size(); ++i) {
    const CanonicalMove& e = expected.moves[i];
    const CanonicalMove& a = actual.moves[i];
    SCOPED_TRACE(name + " move " + std::to_string(i) + " (line " + std::to_string(e.line) + ")");
    EXPECT_EQ(e.kind, a.kind);
    EXPECT_LE((e.end_mm - a.end_mm).cwiseAbs().maxCoeff(), tolerance);
    EXPECT_LE((e.end_abc_deg - a.end_abc_deg).cwiseAbs().maxCoeff(), tolerance);
    if (e.kind == MoveKind::arc) {
      EXPECT_LE((e.center_mm - a.center_mm).cwiseAbs().maxCoeff(), tolerance);
      EXPECT_EQ(e.normal, a.normal);
      EXPECT_EQ(e.turns, a.turns);
      EXPECT_EQ(e.plane, a.plane);
    }
    EXPECT_NEAR(e.feed_mm_min, a.feed_mm_min, tolerance * std::max(1.0, e.feed_mm_min));
    EXPECT_EQ(e.inverse_time, a.inverse_time);
    EXPECT_DOUBLE_EQ(e.inverse_time_per_min, a.inverse_time_per_min);
    EXPECT_DOUBLE_EQ(e.dwell_s, a.dwell_s);
    EXPECT_EQ(e.exact_stop, a.exact_stop);
    EXPECT_NEAR(e.path_tolerance_mm, a.path_tolerance_mm, tolerance);
  }
  ASSERT_EQ(expected.events.size(), actual.events.size()) << name;
  for (std::size_t i = 0; i < expected.events.size(); ++i) {
    EXPECT_EQ(expected.events[i].what, actual.events[i].what) << name << " event " << i;
    EXPECT_EQ(moves_before(expected, expected.events[i]), moves_before(actual, actual.events[i]))
        << name << " event " << expected.events[i].what;
  }
}

const CanonicalMove* first_with_tool_length(const CanonicalProgram& program) {
  for (const CanonicalMove& m : program.moves)
    if (m.tool_length_mm != 0.0) return &m;
  return nullptr;
}

// Round trip of every conformance program at `options`; returns how many were compared (not G43 ones).
int round_trip_conformance(const GcodeWriteOptions& options, double tolerance) {
  int compared = 0;
  int refused = 0;
  for (const fs::path& path : gcode_writer_conformance_programs()) {
    const std::string name = path.filename().string();
    auto original = pkm::program::load_part_program(path.string(), with_tool_table());
    if (!original) {
      ADD_FAILURE() << original.error().message;
      continue;
    }
    auto text = write_gcode(*original, options);
    if (const CanonicalMove* offset = first_with_tool_length(*original)) {
      ++refused;
      if (text) {
        ADD_FAILURE() << name << ": a program with tool length offsets was written";
        continue;
      }
      EXPECT_EQ(text.error().code, ErrorCode::unsupported) << name;
      EXPECT_NE(text.error().message.find(path.string() + ":" + std::to_string(offset->line) + ":"),
                std::string::npos)
          << text.error().message;
      EXPECT_NE(text.error().message.find("not supported"), std::string::npos) << text.error().message;
      continue;
    }
    if (!text) {
      ADD_FAILURE() << name << ": " << text.error().message;
      continue;
    }
    auto again = interpret_gcode(*text, name + " (written)", with_tool_table());
    if (!again) {
      ADD_FAILURE() << again.error().message << "\n" << *text;
      continue;
    }
    expect_same_program(*original, *again, tolerance, name);
    ++compared;
  }
  EXPECT_GT(refused, 0);
  return compared;
}

TEST(GcodeWriter, RoundTripsEveryConformanceProgram) {
  GcodeWriteOptions options;
  options.decimals_mm = 9;
  options.decimals_deg = 9;
  EXPECT_GE(round_trip_conformance(options, 1e-6), 25);
}

TEST(GcodeWriter, RoundTripsAtDefaultDecimalsWithinTheLastDigit) {
  // Four decimals: every value within half a unit of the last digit, centres (start + offset) within one.
  EXPECT_GE(round_trip_conformance({}, 1.01e-4), 25);
}

TEST(GcodeWriter, WritesPreambleMovesAndEnd) {
  const CanonicalProgram program =
      interpret("G21 G90 F500\nG0 X1 Y2 Z3 A10\nG1 X4\nG3 X4 Y8 I0 J3 P2\nG4 P0.5\nM2\n");
  const std::string text = written(program);
  EXPECT_EQ(text,
            "G17 G21 G90 G94 G91.1 G40 G49 G64\n"
            "G0 X1.0000 Y2.0000 Z3.0000 A10.0000 B0.0000 C0.0000 (src 2)\n"
            "G1 X4.0000 Y2.0000 Z3.0000 A10.0000 B0.0000 C0.0000 F500.0000 (src 3)\n"
            "G3 X4.0000 Y8.0000 Z3.0000 A10.0000 B0.0000 C0.0000 I0.0000 J3.0000 P2 (src 4)\n"
            "G4 P0.5 (src 5)\n"
            "M2\n");
}

TEST(GcodeWriter, WritesPlanesFeedModesAndPathControlWhenTheyChange) {
  const CanonicalProgram program = interpret(
      "G21 G90 F500\nG1 X1\nG1 X2\nG18 G2 X4 Z0 I1 K0\nG93 G1 X5 F2\nG0 X6\nG1 X7 F4\nG94 F500 G1 X8\n"
      "G64 P0.05 G1 X9\nG61 G1 X10\n");
  GcodeWriteOptions options;
  options.write_source_lines = false;
  options.decimals_mm = 1;
  options.decimals_deg = 0;
  EXPECT_EQ(written(program, options),
            "G17 G21 G90 G94 G91.1 G40 G49 G64\n"
            "G1 X1.0 Y0.0 Z0.0 A0 B0 C0 F500.0\n"
            "G1 X2.0 Y0.0 Z0.0 A0 B0 C0\n"
            "G18 G2 X4.0 Y0.0 Z0.0 A0 B0 C0 I1.0 K0.0\n"
            "G93 G1 X5.0 Y0.0 Z0.0 A0 B0 C0 F2\n"
            "G0 X6.0 Y0.0 Z0.0 A0 B0 C0\n"
            "G1 X7.0 Y0.0 Z0.0 A0 B0 C0 F4\n"
            "G94 G1 X8.0 Y0.0 Z0.0 A0 B0 C0 F500.0\n"
            "G64 P0.1\n"
            "G1 X9.0 Y0.0 Z0.0 A0 B0 C0\n"
            "G61\n"
            "G1 X10.0 Y0.0 Z0.0 A0 B0 C0\n"
            "M2\n");
}

TEST(GcodeWriter, DecimalsOptionRoundsLengthsAndAnglesSeparately) {
  CanonicalProgram program;
  CanonicalMove m;
  m.line = 3;
  m.kind = MoveKind::line;
  m.end_mm = {1.23456, -0.00001, 100.0};
  m.end_abc_deg = {12.3456, 0.0, -7.26};
  m.feed_mm_min = 1234.5678;
  program.moves.push_back(m);
  GcodeWriteOptions options;
  options.decimals_mm = 2;
  options.decimals_deg = 1;
  const std::string text = written(program, options);
  EXPECT_NE(text.find("G1 X1.23 Y0.00 Z100.00 A12.3 B0.0 C-7.3 F1234.57 (src 3)\n"), std::string::npos)
      << text;
  options.decimals_mm = 13;
  EXPECT_EQ(write_gcode(program, options).error().code, ErrorCode::bad_input);
  options.decimals_mm = 4;
  options.decimals_deg = -1;
  EXPECT_EQ(write_gcode(program, options).error().code, ErrorCode::bad_input);
}

TEST(GcodeWriter, HeaderCommentsComeFirstWithoutParentheses) {
  GcodeWriteOptions options;
  options.header_comments = {"pocket (roughing)", "two\nlines"};
  const std::string text = written(CanonicalProgram{}, options);
  EXPECT_EQ(text.rfind("(pocket roughing)\n(two)\n(lines)\nG17 G21", 0), 0u) << text;
}

TEST(GcodeWriter, EventsAreWrittenBeforeTheMovesOfTheirLine) {
  const CanonicalProgram program =
      interpret("G21 G90 F700\nS10000 M3\nG0 X1 Y1\nT2 M6\nG1 X10 M8\nM9\nS500\nM5\nM30\n");
  const std::string text = written(program);
  const std::size_t spindle = text.find("M3 S10000 (src 2)\n");
  const std::size_t rapid = text.find("G0 X1.0000");
  const std::size_t tool = text.find("M6 T2 (src 4)\n");
  const std::size_t coolant = text.find("M8 (src 5)\nG1 X10.0000");
  const std::size_t end = text.find("M9 (src 6)\nS500 (src 7)\nM5 (src 8)\nM2\n");
  for (const std::size_t at : {spindle, rapid, tool, coolant, end}) ASSERT_NE(at, std::string::npos) << text;
  EXPECT_LT(spindle, rapid);
  EXPECT_LT(rapid, tool);
  EXPECT_LT(tool, coolant);
  EXPECT_LT(coolant, end);
  expect_same_program(program, interpret(text), 1e-9, "events");
}

TEST(GcodeWriter, EventsThatAreNotGcodeBecomeComments) {
  CanonicalProgram program;
  program.events = {{1, "LOADTL/3"}, {2, "PPRINT (rough) pass"}, {2, "M3 S1000"}};
  GcodeWriteOptions options;
  options.write_source_lines = false;
  EXPECT_NE(written(program, options).find("(LOADTL/3)\n(PPRINT rough pass)\nM3 S1000\nM2\n"),
            std::string::npos);
}

TEST(GcodeWriter, SourceLinesCanBeLeftOut) {
  const CanonicalProgram program = interpret("G21 G90 F500\nM8\nG1 X1\n");
  GcodeWriteOptions options;
  options.write_source_lines = false;
  EXPECT_EQ(written(program, options).find("(src"), std::string::npos);
}

TEST(GcodeWriter, ToolAxisOrientationIsAnErrorNamingTheLine) {
  CanonicalProgram program;
  program.source = "part.cls";
  CanonicalMove m;
  m.line = 1;
  m.feed_mm_min = 100.0;
  program.moves.push_back(m);
  m.line = 7;
  m.orientation = OrientationSource::tool_axis;
  m.tool_axis = Eigen::Vector3d(0.0, 0.6, 0.8);
  program.moves.push_back(m);
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().code, ErrorCode::unsupported);
  EXPECT_EQ(text.error().message.rfind("part.cls:7: ", 0), 0u) << text.error().message;
  EXPECT_NE(text.error().message.find("tool-axis"), std::string::npos) << text.error().message;
}

TEST(GcodeWriter, ToolLengthOffsetIsNotSupported) {
  const CanonicalProgram program = interpret("G21 G90 F500\nG1 X1\nT1 M6\nG43 H1\nG1 X2\n");
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().code, ErrorCode::unsupported);
  EXPECT_EQ(text.error().message.rfind("t.ngc:5: ", 0), 0u) << text.error().message;
  EXPECT_NE(text.error().message.find("not supported"), std::string::npos) << text.error().message;
}

TEST(GcodeWriter, ObliqueArcIsAnError) {
  CanonicalProgram program;
  CanonicalMove m;
  m.line = 4;
  m.kind = MoveKind::arc;
  m.end_mm = {0.0, 0.0, 0.0};
  m.center_mm = {5.0, 0.0, 0.0};
  m.normal = Eigen::Vector3d(0.0, 1.0, 1.0).normalized();
  m.feed_mm_min = 100.0;
  program.moves.push_back(m);
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().code, ErrorCode::unsupported);
  EXPECT_EQ(text.error().message.rfind("line 4: ", 0), 0u) << text.error().message;
}

TEST(GcodeWriter, ArcNormalsComputedElsewhereMayBeOffTheAxisByRounding) {
  CanonicalProgram program;
  program.start_mm = {10.0, 0.0, 0.0};
  CanonicalMove m;
  m.line = 2;
  m.kind = MoveKind::arc;
  m.end_mm = {0.0, 10.0, -1.0};
  m.center_mm = {0.0, 0.0, 0.0};
  m.normal = Eigen::Vector3d(1e-12, 0.0, -1.0).normalized();
  m.feed_mm_min = 100.0;
  program.moves.push_back(m);
  GcodeWriteOptions options;
  options.write_source_lines = false;
  EXPECT_NE(written(program, options)
                .find("G2 X0.0000 Y10.0000 Z-1.0000 A0.0000 B0.0000 C0.0000 I-10.0000 "
                      "J0.0000 F100.0000\n"),
            std::string::npos);
}

TEST(GcodeWriter, ArcThatRoundingWouldTurnIntoAFullCircleIsAnError) {
  // A sweep of 1e-7 rad on a 10 mm circle: at 4 decimals the end rounds onto the start, a full circle.
  CanonicalProgram program;
  program.start_mm = {10.0, 0.0, 0.0};
  CanonicalMove m;
  m.line = 9;
  m.kind = MoveKind::arc;
  m.end_mm = {10.0 * std::cos(1e-7), 10.0 * std::sin(1e-7), 0.0};
  m.feed_mm_min = 100.0;
  program.moves.push_back(m);
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message.rfind("line 9: ", 0), 0u) << text.error().message;
  EXPECT_NE(text.error().message.find("more decimals"), std::string::npos) << text.error().message;
  GcodeWriteOptions fine;
  fine.decimals_mm = 9;
  EXPECT_TRUE(write_gcode(program, fine));
}

TEST(GcodeWriter, SpiralBeyondTheMillimetreToleranceIsAnError) {
  // Accepted in G20 (within 0.002·√2 inch), but more than G21's 0.02·√2 mm and 0.1 % of the radius.
  const CanonicalProgram program = interpret("G20 G90 F10\nG0 X1 Y0\nG3 X-1.002 Y0 I-1 J0\n");
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message.rfind("t.ngc:3: ", 0), 0u) << text.error().message;
}

TEST(GcodeWriter, FeedMoveWithoutAFeedIsAnError) {
  CanonicalProgram program;
  CanonicalMove m;
  m.line = 2;
  program.moves.push_back(m);
  auto text = write_gcode(program, {});
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().code, ErrorCode::bad_input);
}

}  // namespace
