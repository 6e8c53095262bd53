// Cutter radius compensation against LinuxCNC's rs274: every tests/program/conformance/comp/*.ngc (written by
// hand: kNN_*, or generated from a seed: rNN_random) is read by a minimal reader here (G0 G1 G2 G3 G4, G17
// G18 G19, G20 G21, G40 G41 G42 G41.1 G42.1 with D, X Y Z A B C I J K F P, M0 M1 M2 M30), its moves driven
// through pkm's CutterCompensation, and the moves that come out compared with the canonical calls rs274
// printed (NAME.rs274, scripts/regen-comp-golden.sh): kind, end (A B C too) and arc centre to 1e-4 in program
// units, turn direction and count, dwells. Where rs274 refused the program, pkm must refuse it too, with the
// same message, on the same block, after the same moves.
#include "program/ngc_cutter_compensation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "program/gcode_arc.hpp"

namespace {

using pkm::program::CanonicalMove;
using pkm::program::MoveKind;
using pkm::program::Plane;
using pkm::program::gcode::LineRef;
using pkm::program::ngc::CompensationSide;
using pkm::program::ngc::CutterCompensation;

namespace fs = std::filesystem;

fs::path comp_test_dir() {
  return fs::path(PKM_SOURCE_DIR) / "tests" / "program" / "conformance" / "comp";
}

std::vector<std::string> comp_test_read_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string comp_test_trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// ---- rs274's answer -------------------------------------------------------------------------------------

struct CompTestCanon {
  MoveKind kind = MoveKind::line;
  Eigen::Vector3d end = Eigen::Vector3d::Zero();     ///< program units
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();     ///< A, B, C (degrees)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< arcs: in the plane's (first, second) frame
  int turn = 0;                                      ///< arcs: signed, > 0 counter-clockwise in that frame
  double dwell_s = 0.0;
  Plane plane = Plane::xy;
};

struct CompTestGolden {
  std::vector<CompTestCanon> moves;
  std::string error;        ///< rs274's message, empty when it ran to the end
  std::string error_block;  ///< the block it stopped on
};

std::vector<double> comp_test_numbers(const std::string& args) {
  std::vector<double> v;
  std::stringstream ss(args);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      v.push_back(std::stod(item));
    } catch (...) {
      v.push_back(0.0);
    }
  }
  return v;
}

CompTestGolden comp_test_read_golden(const fs::path& path) {
  static const std::regex call(R"(^\s*\d+ N\.\.\.\.\. (\w+)\((.*)\)\s*$)");
  CompTestGolden g;
  Plane plane = Plane::xy;
  std::vector<std::string> messages;
  for (const std::string& line : comp_test_read_lines(path)) {
    std::smatch m;
    if (!std::regex_match(line, m, call)) {
      if (!comp_test_trim(line).empty()) messages.push_back(comp_test_trim(line));
      continue;
    }
    const std::string name = m[1];
    const std::string args = m[2];
    if (name == "SELECT_PLANE") {
      plane = args.find("XZ") != std::string::npos   ? Plane::zx
              : args.find("YZ") != std::string::npos ? Plane::yz
                                                     : Plane::xy;
      continue;
    }
    const std::vector<double> v = comp_test_numbers(args);
    CompTestCanon c;
    c.plane = plane;
    if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") {
      c.kind = name == "STRAIGHT_FEED" ? MoveKind::line : MoveKind::rapid;
      c.end = {v[0], v[1], v[2]};
      c.abc = {v[3], v[4], v[5]};
    } else if (name == "ARC_FEED") {
      c.kind = MoveKind::arc;
      const auto axes = pkm::program::gcode::axes_of(plane);
      c.end[axes.first] = v[0];
      c.end[axes.second] = v[1];
      c.end[axes.normal] = v[5];
      c.centre = {v[2], v[3]};
      c.turn = static_cast<int>(v[4]);
      c.abc = {v[6], v[7], v[8]};
    } else if (name == "DWELL") {
      c.kind = MoveKind::dwell;
      c.dwell_s = v[0];
    } else {
      continue;
    }
    g.moves.push_back(c);
  }
  if (!messages.empty()) g.error = messages[0];
  if (messages.size() > 1) g.error_block = messages[1];
  return g;
}

// ---- pkm's answer ---------------------------------------------------------------------------------------

struct CompTestWord {
  char letter;
  double value;
  int column;  ///< 1-based
};

std::vector<CompTestWord> comp_test_words(const std::string& text) {
  std::vector<CompTestWord> words;
  size_t i = 0;
  while (i < text.size()) {
    const char ch = text[i];
    if (ch == '(') {
      i = text.find(')', i);
      if (i == std::string::npos) break;
      ++i;
    } else if (ch == ';') {
      break;
    } else if (std::isalpha(static_cast<unsigned char>(ch))) {
      size_t used = 0;
      const double value = std::stod(text.substr(i + 1), &used);
      words.push_back({static_cast<char>(std::toupper(ch)), value, static_cast<int>(i) + 1});
      i += 1 + used;
    } else {
      ++i;
    }
  }
  return words;
}

std::map<int, double> comp_test_tool_diameters_in() {
  std::map<int, double> diameters;
  for (const std::string& line : comp_test_read_lines(comp_test_dir() / "tools.tbl")) {
    const std::string data = line.substr(0, line.find(';'));
    std::istringstream in(data);
    std::string word;
    int tool = -1;
    double diameter = 0.0;
    while (in >> word) {
      if (word[0] == 'T') tool = std::stoi(word.substr(1));
      if (word[0] == 'D') diameter = std::stod(word.substr(1));
    }
    if (tool >= 0) diameters[tool] = diameter;
  }
  return diameters;
}

struct CompTestRun {
  std::vector<CanonicalMove> moves;
  std::optional<pkm::Error> error;
  double scale_mm = 1.0;  ///< mm per program unit at the end
};

/// The modal state of the minimal reader.
struct CompTestState {
  double scale_mm = 1.0;
  Plane plane = Plane::xy;
  int motion = 0;  ///< 0 1 2 3
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d abc_deg = Eigen::Vector3d::Zero();
};

/// One block: what it asks for, in rs274's order of execution (dwell, plane, units, compensation, motion,
/// stop).
struct CompTestBlock {
  std::optional<double> dwell_s;
  std::optional<Plane> plane;
  int plane_column = 0;
  std::optional<double> scale_mm;
  int comp_code = -1;  ///< 400, 410, 420, 411, 421
  int comp_column = 0;
  std::optional<double> d_word;
  bool motion = false;
  int motion_column = 1;
  std::map<char, double> axes;
  int turns = 1;  ///< G2/G3 P
  bool stop = false;
};

CompTestBlock comp_test_block(const std::vector<CompTestWord>& words, CompTestState& state) {
  CompTestBlock b;
  bool g4 = false;
  double p_word = 0.0;
  for (const CompTestWord& w : words) {
    const int code = static_cast<int>(std::lround(w.value * 10));
    if (w.letter == 'G') {
      if (code <= 30) {
        state.motion = code / 10;
        b.motion = true;
        b.motion_column = w.column;
      } else if (code == 40) {
        g4 = true;
      } else if (code >= 170 && code <= 190) {
        b.plane = code == 170 ? Plane::xy : code == 180 ? Plane::zx : Plane::yz;
        b.plane_column = w.column;
      } else if (code == 200 || code == 210) {
        b.scale_mm = code == 200 ? 25.4 : 1.0;
      } else if (code == 400 || code == 410 || code == 420 || code == 411 || code == 421) {
        b.comp_code = code;
        b.comp_column = w.column;
      }
    } else if (w.letter == 'M') {
      if (code == 0 || code == 10 || code == 20 || code == 300) b.stop = true;
    } else if (w.letter == 'D') {
      b.d_word = w.value;
    } else if (w.letter == 'P') {
      p_word = w.value;
    } else if (std::string("XYZIJKABC").find(w.letter) != std::string::npos) {
      b.axes[w.letter] = w.value;
      b.motion = true;
    }
  }
  if (g4) {
    b.dwell_s = p_word;
  } else if (p_word > 0.0) {
    b.turns = static_cast<int>(std::lround(p_word));
  }
  return b;
}

CanonicalMove comp_test_motion(const CompTestBlock& b, const CompTestState& state, int line) {
  CanonicalMove m;
  m.line = line;
  m.source_line = line;
  m.plane = state.plane;
  m.feed_mm_min = 10.0;
  m.kind = state.motion == 0 ? MoveKind::rapid : state.motion == 1 ? MoveKind::line : MoveKind::arc;
  m.end_mm = state.position_mm;
  const std::string xyz = "XYZ";
  for (int i = 0; i < 3; ++i)
    if (b.axes.count(xyz[i])) m.end_mm[i] = b.axes.at(xyz[i]) * state.scale_mm;
  const std::string abc = "ABC";
  m.end_abc_deg = state.abc_deg;
  for (int i = 0; i < 3; ++i)
    if (b.axes.count(abc[i])) m.end_abc_deg[i] = b.axes.at(abc[i]);
  if (m.kind == MoveKind::arc) {
    const std::string ijk = "IJK";
    m.center_mm = state.position_mm;
    for (int i = 0; i < 3; ++i)
      if (b.axes.count(ijk[i])) m.center_mm[i] += b.axes.at(ijk[i]) * state.scale_mm;
    const auto axes = pkm::program::gcode::axes_of(state.plane);
    m.center_mm[axes.normal] = state.position_mm[axes.normal];
    const Eigen::Vector3d n = pkm::program::gcode::plane_normal(state.plane);
    m.normal = state.motion == 3 ? n : Eigen::Vector3d(-n);
    m.turns = b.turns;
  }
  return m;
}

/// Executes one block; false once an error stops the program.
bool comp_test_execute(const CompTestBlock& b, CompTestState& state, CutterCompensation& comp,
                       const LineRef& where, CompTestRun& run) {
  static const std::map<int, double> diameters_in = comp_test_tool_diameters_in();
  auto fail = [&](const pkm::Status& s) {
    if (s) return false;
    run.error = s.error();
    return true;
  };
  if (b.dwell_s) {
    CanonicalMove dwell;
    dwell.kind = MoveKind::dwell;
    dwell.line = where.line;
    dwell.dwell_s = *b.dwell_s;
    dwell.end_mm = state.position_mm;
    if (fail(comp.move(dwell, where, 1, run.moves))) return false;
  }
  if (b.plane) {
    if (fail(comp.select_plane(*b.plane, where, b.plane_column))) return false;
    state.plane = *b.plane;
  }
  if (b.scale_mm) {
    state.scale_mm = *b.scale_mm;
    comp.set_inch(*b.scale_mm != 1.0);
  }
  if (b.comp_code == 400 && fail(comp.stop(where, b.comp_column))) return false;
  if (b.comp_code > 400) {
    const bool diameter_word = b.comp_code % 10 == 1;
    const double diameter =
        diameter_word ? b.d_word.value_or(0.0) : diameters_in.at(int(b.d_word.value_or(0)));
    const double radius_mm = diameter / 2.0 * (diameter_word ? state.scale_mm : 25.4);
    const auto side = b.comp_code / 10 == 41 ? CompensationSide::left : CompensationSide::right;
    if (fail(comp.start(side, radius_mm, state.plane, where, b.comp_column))) return false;
  }
  if (b.motion) {
    const CanonicalMove m = comp_test_motion(b, state, where.line);
    if (fail(comp.move(m, where, b.motion_column, run.moves))) return false;
    state.position_mm = m.end_mm;
    state.abc_deg = m.end_abc_deg;
  }
  if (b.stop && fail(comp.flush(run.moves, where, 1))) return false;
  return true;
}

CompTestRun comp_test_run(const fs::path& program) {
  CompTestRun run;
  CompTestState state;
  CutterCompensation comp;
  comp.set_position(Eigen::Vector3d::Zero());
  const std::string source = program.filename().string();
  const std::vector<std::string> lines = comp_test_read_lines(program);
  for (size_t i = 0; i < lines.size(); ++i) {
    const LineRef where{source, static_cast<int>(i) + 1};
    const CompTestBlock b = comp_test_block(comp_test_words(lines[i]), state);
    if (!comp_test_execute(b, state, comp, where, run)) break;
  }
  run.scale_mm = state.scale_mm;
  return run;
}

// ---- comparison -----------------------------------------------------------------------------------------

std::vector<std::string> comp_test_programs() {
  std::vector<std::string> names;
  if (!fs::exists(comp_test_dir())) return names;
  for (const auto& entry : fs::directory_iterator(comp_test_dir()))
    if (entry.path().extension() == ".ngc") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

void comp_test_compare(const std::string& name) {
  SCOPED_TRACE(name);
  const CompTestGolden golden = comp_test_read_golden(comp_test_dir() / (name + ".rs274"));
  const CompTestRun run = comp_test_run(comp_test_dir() / (name + ".ngc"));
  // rs274 prints in program units (no suite program switches units).
  const double unit_mm = run.scale_mm;
  constexpr double kTolerance = 1e-4;
  ASSERT_EQ(run.moves.size(), golden.moves.size())
      << (run.error ? run.error->message : std::string("no error"));
  for (size_t i = 0; i < run.moves.size(); ++i) {
    SCOPED_TRACE("move " + std::to_string(i + 1) + ", line " + std::to_string(run.moves[i].line));
    const CanonicalMove& m = run.moves[i];
    const CompTestCanon& g = golden.moves[i];
    ASSERT_EQ(static_cast<int>(m.kind), static_cast<int>(g.kind));
    if (g.kind == MoveKind::dwell) {
      EXPECT_NEAR(m.dwell_s, g.dwell_s, 1e-9);
      continue;
    }
    EXPECT_LT((m.end_mm / unit_mm - g.end).cwiseAbs().maxCoeff(), kTolerance)
        << "pkm " << (m.end_mm / unit_mm).transpose() << " rs274 " << g.end.transpose();
    EXPECT_LT((m.end_abc_deg - g.abc).cwiseAbs().maxCoeff(), kTolerance)
        << "pkm " << m.end_abc_deg.transpose() << " rs274 " << g.abc.transpose();
    if (g.kind != MoveKind::arc) continue;
    const auto axes = pkm::program::gcode::axes_of(g.plane);
    const Eigen::Vector2d centre(m.center_mm[axes.first] / unit_mm, m.center_mm[axes.second] / unit_mm);
    EXPECT_LT((centre - g.centre).cwiseAbs().maxCoeff(), kTolerance)
        << "pkm " << centre.transpose() << " rs274 " << g.centre.transpose();
    const int turn = (m.normal.dot(pkm::program::gcode::plane_normal(g.plane)) > 0 ? 1 : -1) * m.turns;
    EXPECT_EQ(turn, g.turn);
  }
  if (golden.error.empty()) {
    EXPECT_FALSE(run.error.has_value()) << run.error->message;
    return;
  }
  ASSERT_TRUE(run.error.has_value()) << "rs274 refused: " << golden.error;
  const std::string& message = run.error->message;
  EXPECT_TRUE(message.size() >= golden.error.size() &&
              message.compare(message.size() - golden.error.size(), golden.error.size(), golden.error) == 0)
      << "pkm: " << message << "\nrs274: " << golden.error;
  const std::vector<std::string> lines = comp_test_read_lines(comp_test_dir() / (name + ".ngc"));
  ASSERT_GE(run.error->location.line, 1);
  EXPECT_EQ(comp_test_trim(lines.at(run.error->location.line - 1)), golden.error_block);
}

class CompTestGoldenPrograms : public ::testing::TestWithParam<std::string> {};

TEST_P(CompTestGoldenPrograms, MatchesRs274) {
  comp_test_compare(GetParam());
}

INSTANTIATE_TEST_SUITE_P(CutterCompensation, CompTestGoldenPrograms,
                         ::testing::ValuesIn(comp_test_programs()),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

TEST(CutterCompensation, SuiteHasHandWrittenAndGeneratedPrograms) {
  const std::vector<std::string> names = comp_test_programs();
  const auto count = [&](char first) {
    return std::count_if(names.begin(), names.end(), [&](const std::string& n) { return n[0] == first; });
  };
  EXPECT_GE(count('k'), 15);
  EXPECT_GE(count('r'), 80);
  int refused = 0;
  for (const std::string& n : names)
    if (n[0] == 'r' && !comp_test_read_golden(comp_test_dir() / (n + ".rs274")).error.empty()) ++refused;
  EXPECT_GE(refused, 1) << "the generated programs should include some rs274 refuses";
}

// ---- the contract beyond rs274's printout ---------------------------------------------------------------

CanonicalMove comp_test_line(double x_mm, double y_mm, int line, MoveKind kind = MoveKind::line) {
  CanonicalMove m;
  m.kind = kind;
  m.end_mm = {x_mm, y_mm, 0.0};
  m.line = line;
  m.source_line = line;
  m.feed_mm_min = 100.0 * line;
  return m;
}

TEST(CutterCompensation, PassesMovesThroughWhenOff) {
  CutterCompensation comp;
  const std::string source = "prog.ngc";
  std::vector<CanonicalMove> out;
  const CanonicalMove m = comp_test_line(10, 5, 1);
  ASSERT_TRUE(comp.move(m, LineRef{source, 1}, out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].end_mm, m.end_mm);
  EXPECT_FALSE(comp.active());
  EXPECT_EQ(comp.tool_position_mm(), m.end_mm);
}

TEST(CutterCompensation, KeepsNonGeometricFieldsOfTheMoveEachOutputComesFrom) {
  CutterCompensation comp;
  const std::string source = "prog.ngc";
  std::vector<CanonicalMove> out;
  ASSERT_TRUE(comp.start(CompensationSide::left, 2.0, Plane::xy, LineRef{source, 1}, 1));
  EXPECT_TRUE(comp.active());
  ASSERT_TRUE(comp.move(comp_test_line(0, 20, 2), LineRef{source, 2}, out));
  EXPECT_TRUE(out.empty()) << "the entry move waits for the next one";
  ASSERT_TRUE(comp.move(comp_test_line(20, 20, 3), LineRef{source, 3}, out));
  // Convex corner: the entry line, then the corner arc (made for line 3).
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].line, 2);
  EXPECT_DOUBLE_EQ(out[0].feed_mm_min, 200.0);
  EXPECT_EQ(out[1].kind, MoveKind::arc);
  EXPECT_EQ(out[1].line, 3);
  EXPECT_DOUBLE_EQ(out[1].feed_mm_min, 300.0);
  EXPECT_NEAR((out[1].end_mm - Eigen::Vector3d(0, 22, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((comp.tool_position_mm() - Eigen::Vector3d(20, 22, 0)).norm(), 0.0, 1e-12);
  ASSERT_TRUE(comp.stop(LineRef{source, 4}, 1));
  ASSERT_TRUE(comp.move(comp_test_line(30, 30, 5), LineRef{source, 5}, out));
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[2].line, 3);
  EXPECT_NEAR((out[2].end_mm - Eigen::Vector3d(20, 22, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(out[3].end_mm, Eigen::Vector3d(30, 30, 0));
}

TEST(CutterCompensation, QueuedDwellHappensWhereTheMoveBeforeItFinallyEnds) {
  CutterCompensation comp;
  const std::string source = "prog.ngc";
  std::vector<CanonicalMove> out;
  comp.set_position(Eigen::Vector3d(0, -20, 0));
  ASSERT_TRUE(comp.start(CompensationSide::left, 1.0, Plane::xy, LineRef{source, 1}, 1));
  ASSERT_TRUE(comp.move(comp_test_line(0, -10, 2), LineRef{source, 2}, out));
  ASSERT_TRUE(comp.move(comp_test_line(0, 0, 3), LineRef{source, 3}, out));
  CanonicalMove dwell;
  dwell.kind = MoveKind::dwell;
  dwell.dwell_s = 1.5;
  dwell.line = 4;
  ASSERT_TRUE(comp.move(dwell, LineRef{source, 4}, out));
  // Turning left with the tool on the left: a concave corner pulls line 3's end back to (-1, -1).
  ASSERT_TRUE(comp.move(comp_test_line(-10, 0, 5), LineRef{source, 5}, out));
  ASSERT_EQ(out.size(), 3u);
  EXPECT_NEAR((out[0].end_mm - Eigen::Vector3d(-1, -10, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((out[1].end_mm - Eigen::Vector3d(-1, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(out[2].kind, MoveKind::dwell);
  EXPECT_EQ(out[2].line, 4);
  EXPECT_DOUBLE_EQ(out[2].dwell_s, 1.5);
  EXPECT_EQ(out[2].end_mm, out[1].end_mm);
  ASSERT_TRUE(comp.flush(out));
  ASSERT_EQ(out.size(), 4u);
  EXPECT_NEAR((out[3].end_mm - Eigen::Vector3d(-10, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(comp.active()) << "flush keeps compensation on";
}

TEST(CutterCompensation, ZeroRadiusPassesMovesThrough) {
  CutterCompensation comp;
  const std::string source = "prog.ngc";
  std::vector<CanonicalMove> out;
  ASSERT_TRUE(comp.start(CompensationSide::right, 0.0, Plane::xy, LineRef{source, 1}, 1));
  ASSERT_TRUE(comp.move(comp_test_line(1, 0, 2), LineRef{source, 2}, out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].end_mm, Eigen::Vector3d(1, 0, 0));
}

TEST(CutterCompensation, ErrorsCarryLineAndColumn) {
  const std::string source = "prog.ngc";
  {
    CutterCompensation comp;
    const pkm::Status s = comp.start(CompensationSide::left, 1.0, Plane::yz, LineRef{source, 3}, 5);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().message, "prog.ngc:3:5: Cutter radius compensation allowed only in XY, XZ planes");
    EXPECT_EQ(s.error().location.line, 3);
    EXPECT_EQ(s.error().location.column, 5);
  }
  {
    CutterCompensation comp;
    ASSERT_TRUE(comp.start(CompensationSide::left, 1.0, Plane::xy, LineRef{source, 3}, 1));
    const pkm::Status s = comp.start(CompensationSide::right, 1.0, Plane::xy, LineRef{source, 4}, 9);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().message, "prog.ngc:4:9: Cannot turn cutter radius comp on when on");
  }
  {
    CutterCompensation comp;
    ASSERT_TRUE(comp.select_plane(Plane::zx, LineRef{source, 2}, 1)) << "off: any plane";
    ASSERT_TRUE(comp.start(CompensationSide::left, 1.0, Plane::zx, LineRef{source, 3}, 1));
    ASSERT_TRUE(comp.select_plane(Plane::zx, LineRef{source, 4}, 3)) << "the same plane again";
    const pkm::Status s = comp.select_plane(Plane::xy, LineRef{source, 5}, 3);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().message, "prog.ngc:5:3: Cannot change planes with cutter radius compensation on");
  }
  {
    CutterCompensation comp;
    std::vector<CanonicalMove> out;
    ASSERT_TRUE(comp.start(CompensationSide::left, 1.0, Plane::xy, LineRef{source, 3}, 1));
    const pkm::Status s = comp.move(comp_test_line(0.5, 0, 4), LineRef{source, 4}, 7, out);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().message,
              "prog.ngc:4:7: Length of cutter compensation entry move is not greater than the tool radius");
    EXPECT_EQ(s.error().location.column, 7);
  }
  {
    // A line shorter than the pull-back of a concave corner, reported when the corner is known (at flush).
    CutterCompensation comp;
    std::vector<CanonicalMove> out;
    ASSERT_TRUE(comp.start(CompensationSide::right, 5.0, Plane::xy, LineRef{source, 1}, 1));
    ASSERT_TRUE(comp.move(comp_test_line(0, 20, 2), LineRef{source, 2}, out));
    ASSERT_TRUE(comp.move(comp_test_line(2, 20, 3), LineRef{source, 3}, out));
    const pkm::Status s = comp.move(comp_test_line(2, 0, 4), LineRef{source, 4}, 2, out);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().message,
              "prog.ngc:4:2: Straight feed in concave corner cannot be reached by the tool without gouging");
  }
}

}  // namespace
