// Writing APT CL data (program/cl_writer.hpp): read_cl_data reads the text back into the same moves (to the
// decimals written) on random programs of rapids, lines with tilting tool axes, arcs about any axis and
// dwells; A B C moves come out with their tool axis; what CL data cannot state is refused with its line.
#include "program/cl_writer.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "core/rotation.hpp"
#include "program/part_program.hpp"

namespace pkm::program {
namespace {

CanonicalProgram random_cl_program(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  CanonicalProgram program;
  program.source = "random.cl";
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  const int moves = std::uniform_int_distribution<int>(5, 40)(rng);
  for (int m = 0; m < moves; ++m) {
    CanonicalMove move;
    move.line = m + 1;
    move.orientation = OrientationSource::tool_axis;
    move.tool_axis = Eigen::Vector3d(0.3 * unit(rng), 0.3 * unit(rng), 1.0).normalized();
    const double pick = 0.5 * (unit(rng) + 1.0);
    if (pick < 0.15) {
      move.kind = MoveKind::rapid;
      move.end_mm = at + 50.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    } else if (pick < 0.35 && m > 0) {
      // An arc about a random axis through a centre off the start, ending elsewhere on its circle.
      move.kind = MoveKind::arc;
      move.normal = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
      const Eigen::Vector3d radial =
          Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cross(move.normal).normalized() *
          (5.0 + 20.0 * (unit(rng) + 1.0));
      move.center_mm = at - radial;
      const double sweep = std::numbers::pi * (0.2 + 0.7 * (unit(rng) + 1.0));
      const Eigen::Vector3d turned = Eigen::AngleAxisd(sweep, move.normal) * radial;
      move.end_mm = move.center_mm + turned;
      move.feed_mm_min = 600.0;
    } else if (pick < 0.4 && m > 0) {
      move.kind = MoveKind::dwell;
      move.dwell_s = 0.5;
      move.end_mm = at;
    } else {
      move.kind = MoveKind::line;
      move.end_mm = at + 10.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      move.feed_mm_min = std::round(100.0 + 1000.0 * (unit(rng) + 1.0));
    }
    at = move.end_mm;
    program.moves.push_back(move);
  }
  return program;
}

TEST(ClWriter, ReadsBackTheSameMovesOnRandomPrograms) {
  std::mt19937_64 rng(1506);
  for (int trial = 0; trial < 30; ++trial) {
    SCOPED_TRACE(trial);
    const CanonicalProgram program = random_cl_program(rng);
    ClWriteOptions options;
    options.decimals_mm = 9;
    options.decimals_axis = 12;
    auto text = write_cl_data(program, options);
    ASSERT_TRUE(text.ok()) << text.error().message;
    auto back = read_cl_data(*text, "back.cl");
    ASSERT_TRUE(back.ok()) << back.error().message << "\n" << *text;
    ASSERT_EQ(back->moves.size(), program.moves.size());
    for (std::size_t m = 0; m < program.moves.size(); ++m) {
      const CanonicalMove& a = program.moves[m];
      const CanonicalMove& b = back->moves[m];
      ASSERT_EQ(a.kind, b.kind) << "move " << m;
      EXPECT_LT((a.end_mm - b.end_mm).norm(), 1e-8) << "move " << m;
      if (a.kind == MoveKind::dwell) {
        EXPECT_DOUBLE_EQ(a.dwell_s, b.dwell_s);
        continue;
      }
      EXPECT_LT((a.tool_axis - b.tool_axis).norm(), 1e-10) << "move " << m;
      if (a.kind == MoveKind::line || a.kind == MoveKind::arc) {
        EXPECT_DOUBLE_EQ(a.feed_mm_min, b.feed_mm_min);
      }
      if (a.kind == MoveKind::arc) {
        EXPECT_LT((a.normal - b.normal).norm(), 1e-10) << "move " << m;
        // The reader puts the centre on the axis at the start's height; it is the same axis.
        const Eigen::Vector3d offset = b.center_mm - a.center_mm;
        EXPECT_LT((offset - a.normal * a.normal.dot(offset)).norm(), 1e-7) << "move " << m;
      }
    }
  }
}

TEST(ClWriter, WritesTheToolAxisOfABCMovesAndRefusesWhatCLCannotSay) {
  CanonicalProgram program;
  program.source = "abc.ngc";
  CanonicalMove move;
  move.line = 3;
  move.kind = MoveKind::line;
  move.feed_mm_min = 500;
  move.end_mm = {1, 2, 3};
  move.end_abc_deg = {10, -20, 30};
  program.moves.push_back(move);
  auto text = write_cl_data(program, {});
  ASSERT_TRUE(text.ok()) << text.error().message;
  auto back = read_cl_data(*text, "back.cl");
  ASSERT_TRUE(back.ok()) << back.error().message;
  const Eigen::Vector3d expected =
      rotation_from_angles(AngleConvention::abc, move.end_abc_deg * (std::numbers::pi / 180.0)) *
      Eigen::Vector3d::UnitZ();
  EXPECT_LT((back->moves[0].tool_axis - expected).norm(), 1e-6);

  program.moves[0].inverse_time = true;
  program.moves[0].inverse_time_per_min = 2.0;
  auto refused = write_cl_data(program, {});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("abc.ngc:3"), std::string::npos) << refused.error().message;
  program.moves[0].inverse_time = false;
  program.moves[0].kind = MoveKind::arc;
  program.moves[0].turns = 2;
  EXPECT_FALSE(write_cl_data(program, {}).ok());
  program.moves[0].turns = 1;
  program.moves[0].end_mm.x() = std::nan("");
  EXPECT_FALSE(write_cl_data(program, {}).ok());
}

}  // namespace
}  // namespace pkm::program
