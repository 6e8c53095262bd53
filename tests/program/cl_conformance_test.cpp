// The CL conformance set (tests/program/cl_dialects/): a program written in the style of each CAM system,
// every arc entered along the tangent of the move before it. Read with its own dialect (recognised from the
// text), every arc must continue that move; read with the other arc convention, the reader must say so.
#include <gtest/gtest.h>

#include <string>

#include "program/part_program.hpp"
#include "source_paths.hpp"

namespace pkm::program {
namespace {

struct ConformanceFile {
  const char* name;
  ProgramFormat format;
  std::size_t moves;
  int arcs;
  ProgramFormat other_convention;  // read this way, some arcs must reverse (automatic: no such check)
};

Result<CanonicalProgram> load_conformance(const ConformanceFile& file, ProgramFormat format) {
  InterpretOptions options;
  options.format = format;
  return load_part_program(test::source_path(std::string("tests/program/cl_dialects/") + file.name), options);
}

// The unit direction a move ends in, and the one an arc starts in (counter-clockwise about its normal).
Eigen::Vector3d end_direction(const CanonicalMove& move, const Eigen::Vector3d& start) {
  if (move.kind != MoveKind::arc) return (move.end_mm - start).normalized();
  const Eigen::Vector3d r = move.end_mm - move.center_mm;
  return move.normal.cross(r - move.normal * move.normal.dot(r)).normalized();
}

Eigen::Vector3d arc_start_direction(const CanonicalMove& arc, const Eigen::Vector3d& start) {
  const Eigen::Vector3d r = start - arc.center_mm;
  return arc.normal.cross(r - arc.normal * arc.normal.dot(r)).normalized();
}

bool notes_mention(const CanonicalProgram& p, std::string_view text) {
  for (const std::string& note : p.notes)
    if (note.find(text) != std::string::npos) return true;
  return false;
}

class ClConformance : public ::testing::TestWithParam<ConformanceFile> {};

TEST_P(ClConformance, ArcsContinueTheMoveBeforeThem) {
  const ConformanceFile file = GetParam();
  auto program = load_conformance(file, ProgramFormat::automatic);
  ASSERT_TRUE(program.ok()) << program.error().message;
  EXPECT_EQ(program->format, program_format_name(file.format));
  EXPECT_EQ(program->moves.size(), file.moves);
  EXPECT_FALSE(notes_mention(*program, "start against")) << file.name;
  int arcs = 0;
  Eigen::Vector3d position = program->start_mm;
  const CanonicalMove* previous = nullptr;
  Eigen::Vector3d previous_start = position;
  for (const CanonicalMove& move : program->moves) {
    if (move.kind == MoveKind::arc) {
      ++arcs;
      ASSERT_NE(previous, nullptr) << file.name << " line " << move.line;
      const double cos_turn =
          arc_start_direction(move, position).dot(end_direction(*previous, previous_start));
      EXPECT_GT(cos_turn, 0.999) << file.name << " line " << move.line;
    }
    if (move.kind == MoveKind::dwell) continue;
    previous_start = position;
    previous = &move;
    position = move.end_mm;
  }
  EXPECT_EQ(arcs, file.arcs) << file.name;
  if (file.other_convention == ProgramFormat::automatic) return;
  auto other = load_conformance(file, file.other_convention);
  ASSERT_TRUE(other.ok()) << other.error().message;
  EXPECT_TRUE(notes_mention(*other, "start against the direction of the move before them")) << file.name;
}

INSTANTIATE_TEST_SUITE_P(
    Dialects, ClConformance,
    ::testing::Values(
        ConformanceFile{"nx_rounded_pocket.cls", ProgramFormat::nx, 15, 5, ProgramFormat::apt},
        ConformanceFile{"creo_rounded_profile.ncl", ProgramFormat::creo, 12, 4, ProgramFormat::nx},
        ConformanceFile{"solidworks_rounded_pocket.apt", ProgramFormat::solidworks, 20, 5,
                        ProgramFormat::apt},
        ConformanceFile{"camworks_contour.clt", ProgramFormat::solidworks, 7, 2, ProgramFormat::automatic},
        ConformanceFile{"catia_rounded_pocket.aptsource", ProgramFormat::catia, 14, 4, ProgramFormat::nx}),
    [](const ::testing::TestParamInfo<ConformanceFile>& param) {
      std::string name = param.param.name;
      return name.substr(0, name.find('.'));
    });

// What the set states beyond the arcs: frames, units, helix turns, tool axes.
TEST(ClConformanceDetails, FramesAndAxes) {
  auto nx = load_conformance({"nx_rounded_pocket.cls", ProgramFormat::nx, 0, 0, ProgramFormat::automatic},
                             ProgramFormat::automatic);
  ASSERT_TRUE(nx.ok()) << nx.error().message;
  // MSYS: origin (100,50,0), X along +Y: the CL point (5,0,-2) is (100,55,-2) of the part.
  EXPECT_LT((nx->moves[1].end_mm - Eigen::Vector3d(100, 55, -2)).norm(), 1e-9);
  bool helix = false;
  for (const CanonicalMove& m : nx->moves) helix = helix || m.turns == 3;
  EXPECT_TRUE(helix);
  auto creo =
      load_conformance({"creo_rounded_profile.ncl", ProgramFormat::creo, 0, 0, ProgramFormat::automatic},
                       ProgramFormat::automatic);
  ASSERT_TRUE(creo.ok()) << creo.error().message;
  EXPECT_LT((creo->moves[0].end_mm - Eigen::Vector3d(15, 15, 10)).norm(), 1e-9);  // CSYS moves by (10,20,0)
  auto sw = load_conformance(
      {"solidworks_rounded_pocket.apt", ProgramFormat::solidworks, 0, 0, ProgramFormat::automatic},
      ProgramFormat::automatic);
  ASSERT_TRUE(sw.ok()) << sw.error().message;
  EXPECT_LT((sw->moves.back().tool_axis - Eigen::Vector3d::UnitX()).norm(), 1e-12);  // the side face
  EXPECT_TRUE(notes_mention(*sw, "taken the long way round"));
  auto catia = load_conformance(
      {"catia_rounded_pocket.aptsource", ProgramFormat::catia, 0, 0, ProgramFormat::automatic},
      ProgramFormat::automatic);
  ASSERT_TRUE(catia.ok()) << catia.error().message;
  const Eigen::Vector3d tilted = catia->moves[catia->moves.size() - 2].tool_axis;
  EXPECT_NEAR(std::acos(tilted.z()) * 180.0 / 3.14159265358979, 20.0, 1e-4);
}

}  // namespace
}  // namespace pkm::program
