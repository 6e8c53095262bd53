// Generated CL programs read back against their generator: random 5-axis paths (tool axes tilted up to 40°,
// arcs about random axes in both directions and helices, rapids, dwells, multi-point GOTOs) written the way
// each CAM system writes them (arc convention, number style, units, frames), then read by the reader that
// recognises the dialect from the text. The moves that come back must be the generator's, in the part frame.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "program/part_program.hpp"

namespace pkm::program {
namespace {

struct GeneratedMove {
  MoveKind kind = MoveKind::line;
  Eigen::Vector3d end_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d center_mm = Eigen::Vector3d::Zero();  // arcs: at the start's height
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    // arcs: counter-clockwise about it
  double sweep_rad = 0.0;
  double feed_mm_min = 0.0;
  double dwell_s = 0.0;
};

struct DialectStyle {
  ProgramFormat format;
  bool inches = false;
  bool frame = false;  // NX MSYS / Creo CSYS with a random pose
};

class ClProgramGenerator {
 public:
  ClProgramGenerator(unsigned seed, DialectStyle style) : rng_(seed), style_(style) {
    if (style_.frame) {
      const Eigen::Vector3d axis = random_unit();
      rotation_ = Eigen::AngleAxisd(uniform(-3.0, 3.0), axis).toRotationMatrix();
      origin_mm_ = Eigen::Vector3d(uniform(-200, 200), uniform(-200, 200), uniform(-50, 50));
    }
  }

  std::vector<GeneratedMove> moves;
  std::string text;

  void generate(int segments) {
    header();
    position_ = Eigen::Vector3d(uniform(-50, 50), uniform(-50, 50), uniform(0, 30));
    put(slash("FROM") + triple(to_cl(position_)) + sep() + triple(axis_to_cl(axis_)) + "\n");
    feed(uniform(100, 3000));
    for (int i = 0; i < segments; ++i) {
      const double pick = uniform(0, 1);
      if (pick < 0.45) {
        line(false);
      } else if (pick < 0.55) {
        line(true);
      } else if (pick < 0.62) {
        dwell();
      } else if (pick < 0.7 && style_.format == ProgramFormat::apt) {
        points();
      } else {
        arc();
      }
    }
    put(style_.format == ProgramFormat::nx ? "END-OF-PATH\n" : "FINI\n");
  }

 private:
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  Eigen::Vector3d random_unit() {
    Eigen::Vector3d v;
    do v = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    while (v.norm() < 0.2 || v.norm() > 1.0);
    return v.normalized();
  }
  // A tool axis within 40° of +Z.
  Eigen::Vector3d random_tilt() {
    const double tilt = uniform(0, 40) * std::numbers::pi / 180.0, turn = uniform(0, 2 * std::numbers::pi);
    return {std::sin(tilt) * std::cos(turn), std::sin(tilt) * std::sin(turn), std::cos(tilt)};
  }
  double length_unit() const { return style_.inches ? 25.4 : 1.0; }
  Eigen::Vector3d to_cl(const Eigen::Vector3d& p_mm) const {
    return rotation_.transpose() * (p_mm - origin_mm_) / length_unit();
  }
  Eigen::Vector3d axis_to_cl(const Eigen::Vector3d& a) const { return rotation_.transpose() * a; }
  int decimals() const {
    switch (style_.format) {
      case ProgramFormat::nx:
        return 5;
      case ProgramFormat::creo:
        return 10;
      default:
        return 6;
    }
  }
  std::string num(double v) const {
    std::string s = fmt::format("{:.{}f}", v, decimals());
    if (style_.format == ProgramFormat::solidworks) {  // "25." and ".5" but "-0.5", as SolidWorks CAM writes
      while (s.back() == '0') s.pop_back();
      if (s.rfind("0.", 0) == 0) s.erase(0, 1);
      if (s == "." || s == "-0." || s == "-.") s = "0";
    }
    return s;
  }
  std::string sep() const { return style_.format == ProgramFormat::creo ? ", " : ","; }
  std::string triple(const Eigen::Vector3d& v) const {
    return num(v.x()) + sep() + num(v.y()) + sep() + num(v.z());
  }
  std::string slash(const char* word) const {
    return style_.format == ProgramFormat::creo ? fmt::format("{} / ", word) : fmt::format("{}/", word);
  }
  void put(const std::string& s) { text += s; }

  void header() {
    switch (style_.format) {
      case ProgramFormat::nx:
        put("TOOL PATH/GENERATED,TOOL,MILL\nTLDATA/MILL,10.0000,0.0000,75.0000,0.0000,0.0000\n");
        units();  // before the frame: its origin is a length
        if (style_.frame) put(msys());
        put("$$ centerline data\n");
        break;
      case ProgramFormat::creo:
        put("$$*          Pro/CLfile  Version 8.0 - 8.0.3.0\n$$-> MFGNO / GENERATED\nPARTNO / GENERATED\n");
        units();
        if (style_.frame) put(csys());
        break;
      case ProgramFormat::solidworks:
        put("PARTNO/GENERATED\n$$ CAMWorks generated test program\n");
        units();
        break;
      default:
        put("PARTNO/GENERATED\n");
        units();
        break;
    }
  }
  void units() {
    put(style_.inches ? (style_.format == ProgramFormat::solidworks ? "UNIT/INCHES\n" : "UNITS/INCHES\n")
                      : (style_.format == ProgramFormat::solidworks ? "UNIT/MM\n" : "UNITS/MM\n"));
  }
  std::string msys() const {
    return fmt::format(
        "MSYS/{},{},{}\n",
        fmt::format("{:.4f},{:.4f},{:.4f}", origin_mm_.x() / length_unit(), origin_mm_.y() / length_unit(),
                    origin_mm_.z() / length_unit()),
        fmt::format("{:.12f},{:.12f},{:.12f}", rotation_(0, 0), rotation_(1, 0), rotation_(2, 0)),
        fmt::format("{:.12f},{:.12f},{:.12f}", rotation_(0, 1), rotation_(1, 1), rotation_(2, 1)));
  }
  std::string csys() const {
    std::string rows;
    for (int r = 0; r < 3; ++r) {
      rows += fmt::format("{:.12f}, {:.12f}, {:.12f}, {:.12f}", rotation_(r, 0), rotation_(r, 1),
                          rotation_(r, 2), origin_mm_[r] / length_unit());
      rows += r < 2 ? ",  $\n            " : "\n";
    }
    return "$$-> CSYS / " + rows;
  }

  void feed(double mm_min) {
    feed_mm_min_ = mm_min;
    const double per_unit = mm_min / length_unit();
    const std::string unit = style_.inches ? "IPM" : "MMPM";
    if (style_.format == ProgramFormat::nx)
      put(fmt::format("FEDRAT/{},{:.4f}\n", unit, per_unit));
    else
      put(fmt::format("{}{:.4f}{}{}\n", slash("FEDRAT"), per_unit, sep(), unit));
  }

  void go_to(const Eigen::Vector3d& end_mm, bool axis_changed) {
    std::string values = triple(to_cl(end_mm));
    if (axis_changed) values += sep() + triple(axis_to_cl(axis_));
    put(slash("GOTO") + values + "\n");
  }

  void line(bool rapid) {
    const Eigen::Vector3d end =
        position_ + Eigen::Vector3d(uniform(-30, 30), uniform(-30, 30), uniform(-10, 10));
    const bool change_axis = uniform(0, 1) < 0.5;
    if (change_axis) axis_ = random_tilt();
    if (rapid) put(style_.format == ProgramFormat::solidworks ? "RAPID/\n" : "RAPID\n");
    go_to(end, change_axis);
    moves.push_back(
        {rapid ? MoveKind::rapid : MoveKind::line, end, axis_, {}, {}, 0.0, rapid ? 0.0 : feed_mm_min_});
    if (!rapid) direction_ = (end - position_).normalized();
    position_ = end;
  }

  void points() {  // GOTO/x,y,z,x,y,z,… (the tool axis unchanged)
    std::string values;
    const int count = 3 + static_cast<int>(uniform(0, 2));  // two points would read as a point and an axis
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d end =
          position_ + Eigen::Vector3d(uniform(-20, 20), uniform(-20, 20), uniform(-5, 5));
      values += (k == 0 ? "" : sep()) + triple(to_cl(end));
      moves.push_back({MoveKind::line, end, axis_, {}, {}, 0.0, feed_mm_min_});
      direction_ = (end - position_).normalized();
      position_ = end;
    }
    put(slash("GOTO") + values + "\n");
  }

  void dwell() {
    const double seconds = std::round(uniform(0.1, 3.0) * 100) / 100;
    put(fmt::format("{}{:.2f}\n", slash("DELAY"), seconds));
    moves.push_back({MoveKind::dwell, position_, axis_, {}, {}, 0.0, 0.0, seconds});
  }

  // An arc entered tangentially (a short lead-in line along its start tangent), so that every dialect's
  // convention can be checked by continuity and no arc reverses the move before it.
  void arc() {
    const Eigen::Vector3d normal =
        uniform(0, 1) < 0.6 ? Eigen::Vector3d(0, 0, uniform(0, 1) < 0.5 ? 1 : -1) : random_unit();
    const double radius = uniform(2, 40);
    Eigen::Vector3d radial = normal.unitOrthogonal();
    radial = Eigen::AngleAxisd(uniform(0, 6.28), normal) * radial;
    const Eigen::Vector3d tangent = normal.cross(radial);
    const Eigen::Vector3d start = position_ + tangent * uniform(1, 10);
    go_to(start, false);
    moves.push_back({MoveKind::line, start, axis_, {}, {}, 0.0, feed_mm_min_});
    position_ = start;
    const Eigen::Vector3d center = start - radial * radius;
    const double sweep = uniform(5, 355) * std::numbers::pi / 180.0;
    const double rise = uniform(0, 1) < 0.3 ? uniform(-5, 5) : 0.0;
    const Eigen::Vector3d end = center + Eigen::AngleAxisd(sweep, normal) * (radial * radius) + normal * rise;
    put(circle_record(center, normal, radius, sweep));
    go_to(end, false);
    moves.push_back({MoveKind::arc, end, axis_, center, normal, sweep, feed_mm_min_});
    position_ = end;
  }

  // CIRCLE as each system writes it: the written axis and direction for an arc counter-clockwise about
  // `normal` sweeping `sweep`.
  std::string circle_record(const Eigen::Vector3d& center, const Eigen::Vector3d& normal, double radius,
                            double sweep) {
    const std::string c = triple(to_cl(center));
    const double r = radius / length_unit();
    switch (style_.format) {
      case ProgramFormat::nx:  // clockwise about the written axis; tolerance, ratio, tool values after r
        return fmt::format("CIRCLE/{},{},{},0.0600,0.5000,10.0000,0.0000\n", c, triple(axis_to_cl(-normal)),
                           num(r));
      case ProgramFormat::solidworks: {  // six values; the axis of the shorter arc
        const Eigen::Vector3d written = sweep <= std::numbers::pi ? normal : Eigen::Vector3d(-normal);
        return fmt::format("CIRCLE/{},{}\n", c, triple(axis_to_cl(written)));
      }
      case ProgramFormat::creo:
        return fmt::format("{}{}{}{}{}{}\n", slash("CIRCLE"), c, sep(), triple(axis_to_cl(normal)), sep(),
                           num(r));
      default: {  // generic APT: either the axis alone, or the opposite axis with CLOCKWISE
        if (uniform(0, 1) < 0.5)
          return fmt::format("CIRCLE/{},{},{}\n", c, triple(axis_to_cl(normal)), num(r));
        return fmt::format("CIRCLE/{},{},{},CLOCKWISE\n", c, triple(axis_to_cl(-normal)), num(r));
      }
    }
  }

  std::mt19937 rng_;
  DialectStyle style_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d origin_mm_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d direction_ = Eigen::Vector3d::UnitX();
  double feed_mm_min_ = 0.0;
};

void expect_same_moves(const std::vector<GeneratedMove>& expected, const CanonicalProgram& read,
                       const std::string& context, bool inches) {
  ASSERT_EQ(read.moves.size(), expected.size()) << context;
  const double tol_mm = inches ? 5e-3 : 2e-3;  // written to 4–10 decimals (inches: ×25.4)
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const GeneratedMove& e = expected[i];
    const CanonicalMove& m = read.moves[i];
    const std::string where = fmt::format("{} move {} (line {})", context, i, m.line);
    ASSERT_EQ(m.kind, e.kind) << where;
    EXPECT_LT((m.end_mm - e.end_mm).norm(), tol_mm) << where;
    EXPECT_EQ(m.orientation, OrientationSource::tool_axis) << where;
    EXPECT_LT((m.tool_axis - e.tool_axis).norm(), 1e-4) << where;
    if (e.kind == MoveKind::line || e.kind == MoveKind::arc) {
      EXPECT_NEAR(m.feed_mm_min, e.feed_mm_min, 1e-2 * (1 + e.feed_mm_min / 1000)) << where;
    }
    if (e.kind == MoveKind::dwell) {
      EXPECT_NEAR(m.dwell_s, e.dwell_s, 1e-9) << where;
    }
    if (e.kind == MoveKind::arc) {
      EXPECT_LT((m.normal - e.normal).norm(), 1e-4) << where;  // the direction: the point of it all
      EXPECT_LT((m.center_mm - e.center_mm).norm(), tol_mm) << where;
    }
  }
}

class ClGenerated : public ::testing::TestWithParam<DialectStyle> {};

TEST_P(ClGenerated, ReadBackAsGenerated) {
  const DialectStyle style = GetParam();
  for (unsigned seed = 1; seed <= 40; ++seed) {
    ClProgramGenerator generator(seed * 7919 + static_cast<unsigned>(style.format), style);
    generator.generate(40);
    const std::string context = fmt::format("{} seed {}{}{}", program_format_key(style.format), seed,
                                            style.inches ? " inches" : "", style.frame ? " frame" : "");
    EXPECT_EQ(detect_program_format(generator.text), style.format) << context;
    auto program = read_cl_data(generator.text, "generated.cl");
    ASSERT_TRUE(program.ok()) << context << ": " << program.error().message << "\n" << generator.text;
    expect_same_moves(generator.moves, *program, context, style.inches);
    for (const std::string& note : program->notes)
      EXPECT_EQ(note.find("start against"), std::string::npos) << context << ": " << note;
  }
}

INSTANTIATE_TEST_SUITE_P(Dialects, ClGenerated,
                         ::testing::Values(DialectStyle{ProgramFormat::apt, false, false},
                                           DialectStyle{ProgramFormat::apt, true, false},
                                           DialectStyle{ProgramFormat::nx, false, true},
                                           DialectStyle{ProgramFormat::nx, true, true},
                                           DialectStyle{ProgramFormat::creo, false, true},
                                           DialectStyle{ProgramFormat::solidworks, false, false},
                                           DialectStyle{ProgramFormat::solidworks, true, false}));

}  // namespace
}  // namespace pkm::program
