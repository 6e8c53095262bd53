// interpret_gcode: RS274/NGC blocks → canonical moves. The modal state (units, distance modes, plane, feed,
// tool length, path control) is carried from block to block; each block is executed in LinuxCNC's order
// (feed mode, F, S, T, M6, spindle, coolant, dwell, plane, units, tool length, path control, distance modes,
// motion, stop), and its coordinates mean what rs274's canonical calls mean (docs/part-programs.md).
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "program/gcode_arc.hpp"
#include "program/gcode_block.hpp"
#include "program/gcode_lexer.hpp"
#include "program/part_program.hpp"
#include "program/text_lines.hpp"
#include "program/tool_table.hpp"

namespace pkm::program {

namespace {

using gcode::Block;
using gcode::LineRef;

constexpr double kMmPerInch = 25.4;

enum class Motion { none, rapid, line, clockwise, counter_clockwise };

Motion motion_of(const gcode::Code& code) {
  switch (code.number) {
    case 0:
      return Motion::rapid;
    case 10:
      return Motion::line;
    case 20:
      return Motion::clockwise;
    case 30:
      return Motion::counter_clockwise;
    default:
      return Motion::none;
  }
}

bool is_arc(Motion m) {
  return m == Motion::clockwise || m == Motion::counter_clockwise;
}

// Where to point at for an error about the block's move: its motion code, else its first axis or arc word.
int motion_column(const Block& b) {
  if (b.g[gcode::g_motion].given()) return b.g[gcode::g_motion].column;
  if (const int axis = b.first_axis_column(); axis > 0) return axis;
  for (const char letter : {'I', 'J', 'K', 'R'})
    if (b[letter].given()) return b[letter].column;
  return 1;
}

bool is_whole(double value) {
  return std::abs(value - std::round(value)) < 1e-6;
}

// Tool numbers and turns are ints; larger values are typing errors, not programs.
constexpr double kLargestCount = 1e6;

struct ModalState {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  ///< program coordinates (rs274's), mm
  Eigen::Vector3d abc_deg = Eigen::Vector3d::Zero();
  Motion motion = Motion::none;  // rs274 starts with motion cancelled (G80)
  Plane plane = Plane::xy;
  bool inch = false;  // rs274 starts in mm
  bool incremental = false;
  bool arc_centre_incremental = true;  // G91.1
  bool inverse_time = false;
  double feed_mm_min = 0.0;  ///< G94 feed; 0 = none programmed
  double tool_length_mm = 0.0;
  int selected_tool = 0;
  int spindle_tool = 0;
  double spindle_speed = 0.0;
  double path_tolerance_mm = -1.0;
  bool exact_stop = false;
};

class Interpreter {
 public:
  Interpreter(const std::string& source, const InterpretOptions& options, const ToolTable* tools)
      : source_(source), options_(options), tools_(tools) {
    state_.position_mm = options.start_mm;
    state_.abc_deg = options.start_abc_deg;
  }

  Status run(std::string_view text, CanonicalProgram& program) {
    program_ = &program;
    // A UTF-8 byte-order mark (some Windows editors write one) is not part of the first block.
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    program.source = source_;
    program.start_mm = options_.start_mm;
    program.start_abc_deg = options_.start_abc_deg;
    // Most blocks of a CAM program are one move; a line of G-code is rarely shorter than 12 bytes.
    program.moves.reserve(text.size() / 12 + 16);
    gcode::LexedLine lexed;
    lexed.words.reserve(16);
    Block block;
    bool seen_block = false;
    int line_number = 0;
    std::string_view line;
    TextLines lines(text);
    while (lines.next(line, line_number)) {
      if (options_.block_delete && starts_with_slash(line)) continue;
      const LineRef where{source_, line_number};
      if (auto lexing = gcode::lex_line(line, where, lexed); !lexing) return lexing.error();
      if (lexed.percent) {
        // A '%' before the first block opens the program; any other ends it.
        if (!seen_block) {
          seen_block = true;
          continue;
        }
        program.end_line = line_number;
        return ok_status();
      }
      if (lexed.words.empty()) continue;
      seen_block = true;
      if (auto built = gcode::build_block(lexed, where, block); !built) return built.error();
      if (auto executed = execute(block, where); !executed) return executed.error();
      if (ended_) {
        program.end_line = line_number;
        return ok_status();
      }
    }
    program.end_line = line_number;
    return ok_status();
  }

 private:
  static bool starts_with_slash(std::string_view line) {
    for (const char c : line) {
      if (c == '/') return true;
      if (c != ' ' && c != '\t') return false;
    }
    return false;
  }

  double length_scale() const { return state_.inch ? kMmPerInch : 1.0; }

  void add_event(int line, std::string what) {
    program_->events.push_back(ProgramEvent{line, std::move(what)});
  }

  Status execute(const Block& b, const LineRef& where);
  Status check_words(const Block& b, const LineRef& where, Motion motion, bool moves) const;
  Status set_tool_length(const Block& b, const LineRef& where);
  Status move(const Block& b, const LineRef& where, Motion motion);
  Status feed_for(const Block& b, const LineRef& where, Motion motion, CanonicalMove& m) const;
  Status arc_move(const Block& b, const LineRef& where, Motion motion, const Eigen::Vector3d& start,
                  CanonicalMove& m) const;

  const std::string& source_;
  const InterpretOptions& options_;
  const ToolTable* tools_;
  CanonicalProgram* program_ = nullptr;
  ModalState state_;
  bool ended_ = false;
};

Status Interpreter::check_words(const Block& b, const LineRef& where, Motion motion, bool moves) const {
  // Axis words need a motion mode to use them.
  if (const int axis_column = b.first_axis_column(); axis_column > 0 && motion == Motion::none) {
    if (b.g[gcode::g_motion].given())
      return gcode::error_at(where, axis_column, "axis words with G80 (motion cancelled)");
    return gcode::error_at(where, axis_column, "axis words without a motion mode (G0, G1, G2 or G3)");
  }
  for (const char letter : {'I', 'J', 'K', 'R'}) {
    if (b[letter].given() && !(moves && is_arc(motion)))
      return gcode::error_at(where, b[letter].column,
                             fmt::format("{} word with no G2 or G3 to use it", letter));
  }
  const bool dwell = b.g[gcode::g_non_modal].is(40);
  const bool blend = b.g[gcode::g_path_control].is(640);
  const bool turns = moves && is_arc(motion);
  if (b['P'].given()) {
    const int users = static_cast<int>(dwell) + static_cast<int>(blend) + static_cast<int>(turns);
    if (users == 0)
      return gcode::error_at(where, b['P'].column, "P word with no G2, G3, G4 or G64 to use it");
    if (users > 1)
      return gcode::error_at(where, b['P'].column, "P word claimed by more than one of G2/G3, G4 and G64");
  }
  if (dwell && !b['P'].given())
    return gcode::error_at(where, b.g[gcode::g_non_modal].column, "G4 without a P word (dwell seconds)");
  if (b['H'].given() && !b.g[gcode::g_tool_length].is(430))
    return gcode::error_at(where, b['H'].column, "H word without G43 to use it");
  if (b['F'].given() && b['F'].value < 0.0)
    return gcode::error_at(where, b['F'].column, "negative feed rate F");
  if (b['S'].given() && b['S'].value < 0.0)
    return gcode::error_at(where, b['S'].column, "negative spindle speed S");
  for (const char letter : {'T', 'H'}) {
    const gcode::Value& v = b[letter];
    if (v.given() && (v.value < 0.0 || v.value > kLargestCount || !is_whole(v.value)))
      return gcode::error_at(where, v.column,
                             fmt::format("{} must be a whole number from 0 to 1000000", letter));
  }
  return ok_status();
}

Status Interpreter::execute(const Block& b, const LineRef& where) {
  const gcode::Code& motion_code = b.g[gcode::g_motion];
  const Motion motion = motion_code.given() ? motion_of(motion_code) : state_.motion;
  const bool arc_words = b['I'].given() || b['J'].given() || b['K'].given() || b['R'].given();
  // A block moves when it names a motion code, has an axis word, or gives arc data to a modal G2/G3.
  const bool moves = motion != Motion::none &&
                     (motion_code.given() || b.first_axis_column() > 0 || (is_arc(motion) && arc_words));
  if (auto checked = check_words(b, where, motion, moves); !checked) return checked;

  // Units first: F and every length in this block are read in the units the block ends up in.
  if (b.g[gcode::g_units].given()) state_.inch = b.g[gcode::g_units].is(200);
  const int line = where.line;

  if (const gcode::Code& mode = b.g[gcode::g_feed_mode]; mode.given()) {
    state_.inverse_time = mode.is(930);
    state_.feed_mm_min = 0.0;  // rs274 clears the feed on G93 and G94: the next feed move needs an F
  }
  if (b['F'].given() && !state_.inverse_time) state_.feed_mm_min = b['F'].value * length_scale();

  const gcode::Code& spindle = b.m[gcode::m_spindle];
  if (b['S'].given()) {
    state_.spindle_speed = b['S'].value;
    if (!spindle.given() || spindle.is(50)) add_event(line, fmt::format("S{}", state_.spindle_speed));
  }
  const gcode::Code& tool_change = b.m[gcode::m_tool_change];
  if (b['T'].given()) {
    const int tool = static_cast<int>(std::lround(b['T'].value));
    if (tools_ && tool > 0 && !tools_->find(tool))
      return gcode::error_at(
          where, b['T'].column,
          fmt::format("tool T{} is not in the tool table {}", tool, options_.tool_table_path));
    state_.selected_tool = tool;
    if (!tool_change.given()) add_event(line, fmt::format("T{}", tool));
  }
  if (tool_change.given()) {
    state_.spindle_tool = state_.selected_tool;
    add_event(line, fmt::format("M6 T{}", state_.spindle_tool));
  }
  if (spindle.is(30)) add_event(line, fmt::format("M3 S{}", state_.spindle_speed));
  if (spindle.is(40)) add_event(line, fmt::format("M4 S{}", state_.spindle_speed));
  if (spindle.is(50)) add_event(line, "M5");
  if (const gcode::Code& coolant = b.m[gcode::m_coolant]; coolant.given())
    add_event(line, gcode::code_name('M', coolant.number));

  if (b.g[gcode::g_non_modal].is(40)) {
    const gcode::Value& p = b['P'];
    if (p.value < 0.0) return gcode::error_at(where, p.column, "negative dwell time P");
    CanonicalMove m;
    m.line = line;
    m.kind = MoveKind::dwell;
    m.end_mm = state_.position_mm;
    m.end_abc_deg = state_.abc_deg;
    m.dwell_s = p.value;
    m.plane = state_.plane;
    m.tool_length_mm = state_.tool_length_mm;
    m.path_tolerance_mm = state_.path_tolerance_mm;
    m.exact_stop = state_.exact_stop;
    program_->moves.push_back(m);
  }
  if (const gcode::Code& plane = b.g[gcode::g_plane]; plane.given())
    state_.plane = plane.is(170) ? Plane::xy : (plane.is(180) ? Plane::zx : Plane::yz);
  if (b.g[gcode::g_tool_length].given()) {
    if (auto set = set_tool_length(b, where); !set) return set;
  }
  if (const gcode::Code& control = b.g[gcode::g_path_control]; control.given()) {
    state_.exact_stop = !control.is(640);
    state_.path_tolerance_mm = -1.0;
    if (control.is(640) && b['P'].given()) {
      if (b['P'].value < 0.0) return gcode::error_at(where, b['P'].column, "negative G64 tolerance P");
      if (b['P'].value > 0.0) state_.path_tolerance_mm = b['P'].value * length_scale();
    }
  }
  if (const gcode::Code& distance = b.g[gcode::g_distance]; distance.given())
    state_.incremental = distance.is(910);
  if (const gcode::Code& arc_distance = b.g[gcode::g_arc_distance]; arc_distance.given())
    state_.arc_centre_incremental = arc_distance.is(911);

  state_.motion = motion;
  if (moves) {
    if (auto moved = move(b, where, motion); !moved) return moved;
  }
  if (b.m[gcode::m_stop].given()) ended_ = true;
  return ok_status();
}

Status Interpreter::set_tool_length(const Block& b, const LineRef& where) {
  double length = 0.0;
  if (b.g[gcode::g_tool_length].is(430)) {
    // As LinuxCNC: G43 without H, or with H0, takes the tool in the spindle.
    const bool with_h = b['H'].given() && std::lround(b['H'].value) > 0;
    const int tool = with_h ? static_cast<int>(std::lround(b['H'].value)) : state_.spindle_tool;
    const int column = b['H'].given() ? b['H'].column : b.g[gcode::g_tool_length].column;
    if (tool > 0) {
      if (!tools_)
        return gcode::error_at(where, column,
                               fmt::format("G43 for tool {} needs a tool table, and none was given", tool));
      const ToolEntry* entry = tools_->find(tool);
      if (!entry)
        return gcode::error_at(
            where, column,
            fmt::format("tool {} is not in the tool table {}", tool, options_.tool_table_path));
      length = entry->length_mm;
    }
  }
  // As rs274: the tool tip stays where it is, so its program Z changes by the change of offset.
  state_.position_mm.z() -= length - state_.tool_length_mm;
  state_.tool_length_mm = length;
  return ok_status();
}

Status Interpreter::feed_for(const Block& b, const LineRef& where, Motion motion, CanonicalMove& m) const {
  if (motion == Motion::rapid) return ok_status();
  const char* name = motion == Motion::line ? "G1" : (motion == Motion::clockwise ? "G2" : "G3");
  if (state_.inverse_time) {
    const gcode::Value& f = b['F'];
    if (!f.given())
      return gcode::error_at(where, motion_column(b),
                             fmt::format("{} in inverse-time mode (G93) needs an F word in its block", name));
    if (f.value <= 0.0) return gcode::error_at(where, f.column, "inverse-time F must be greater than 0");
    m.inverse_time = true;
    m.inverse_time_per_min = f.value;
    return ok_status();
  }
  if (state_.feed_mm_min <= 0.0) {
    const int column = b['F'].given() ? b['F'].column : motion_column(b);
    return gcode::error_at(where, column, fmt::format("{} with no feed rate programmed (F)", name));
  }
  m.feed_mm_min = state_.feed_mm_min;
  return ok_status();
}

Status Interpreter::move(const Block& b, const LineRef& where, Motion motion) {
  const double scale = length_scale();
  const Eigen::Vector3d start = state_.position_mm;
  CanonicalMove m;
  m.line = where.line;
  m.plane = state_.plane;
  m.tool_length_mm = state_.tool_length_mm;
  m.path_tolerance_mm = state_.path_tolerance_mm;
  m.exact_stop = state_.exact_stop;
  m.end_mm = start;
  m.end_abc_deg = state_.abc_deg;
  const char linear[3] = {'X', 'Y', 'Z'};
  const char rotary[3] = {'A', 'B', 'C'};
  for (int i = 0; i < 3; ++i) {
    if (const gcode::Value& v = b[linear[i]]; v.given())
      m.end_mm[i] = (state_.incremental ? start[i] : 0.0) + v.value * scale;
    if (const gcode::Value& v = b[rotary[i]]; v.given())
      m.end_abc_deg[i] = (state_.incremental ? state_.abc_deg[i] : 0.0) + v.value;
  }
  if (auto fed = feed_for(b, where, motion, m); !fed) return fed;

  if (motion == Motion::rapid || motion == Motion::line) {
    m.kind = motion == Motion::rapid ? MoveKind::rapid : MoveKind::line;
    if (m.inverse_time) {
      // rs274 reports an inverse-time feed as the equivalent XYZ speed; for rotary-only moves there is none.
      m.feed_mm_min = (m.end_mm - start).norm() * m.inverse_time_per_min;
    }
  } else {
    if (auto arc = arc_move(b, where, motion, start, m); !arc) return arc;
  }
  program_->moves.push_back(m);
  state_.position_mm = m.end_mm;
  state_.abc_deg = m.end_abc_deg;
  return ok_status();
}

Status Interpreter::arc_move(const Block& b, const LineRef& where, Motion motion,
                             const Eigen::Vector3d& start, CanonicalMove& m) const {
  static constexpr char kOffsetLetter[3] = {'I', 'J', 'K'};  // centre offsets along X, Y, Z
  const char* const plane_name =
      state_.plane == Plane::xy ? "G17 (XY)" : (state_.plane == Plane::zx ? "G18 (XZ)" : "G19 (YZ)");
  const char* const name = motion == Motion::clockwise ? "G2" : "G3";
  const gcode::PlaneAxes axes = gcode::axes_of(state_.plane);
  const double scale = length_scale();
  if (const gcode::Value& v = b[kOffsetLetter[axes.normal]]; v.given())
    return gcode::error_at(where, v.column,
                           fmt::format("{} word in a {} arc", kOffsetLetter[axes.normal], plane_name));
  const gcode::Value& first = b[kOffsetLetter[axes.first]];
  const gcode::Value& second = b[kOffsetLetter[axes.second]];
  const gcode::Value& r = b['R'];
  if (r.given() && (first.given() || second.given()))
    return gcode::error_at(where, r.column, "R and I/J/K in one arc: give the centre one way");
  if (!r.given() && !first.given() && !second.given()) {
    return gcode::error_at(where, motion_column(b), fmt::format("{} with no I, J, K or R", name));
  }
  if (const gcode::Value& p = b['P']; p.given()) {
    if (!is_whole(p.value) || p.value < 1.0 || p.value > kLargestCount)
      return gcode::error_at(where, p.column,
                             fmt::format("{} P (turns) must be a whole number from 1 to 1000000", name));
    m.turns = static_cast<int>(std::lround(p.value));
  }
  const bool clockwise = motion == Motion::clockwise;
  const gcode::ArcTolerances tolerances = gcode::arc_tolerances(state_.inch);
  Eigen::Vector3d centre = start;
  if (r.given()) {
    const gcode::ArcProblem problem = gcode::centre_from_radius(start, m.end_mm, r.value * scale, clockwise,
                                                                state_.plane, tolerances, centre);
    if (!problem.message.empty()) return gcode::error_at(where, r.column, problem.message);
  } else {
    for (const gcode::Value* v : {&first, &second}) {
      const int axis = v == &first ? axes.first : axes.second;
      if (state_.arc_centre_incremental) {
        centre[axis] = start[axis] + (v->given() ? v->value * scale : 0.0);
      } else if (v->given()) {
        centre[axis] = v->value * scale;
      } else {
        const int column = first.given() ? first.column : second.column;
        return gcode::error_at(
            where, column,
            fmt::format("{} word missing: absolute arc centres (G90.1) need both", kOffsetLetter[axis]));
      }
    }
    const gcode::ArcProblem problem =
        gcode::check_centre_arc(start, m.end_mm, centre, state_.plane, tolerances);
    const int column = first.given() ? first.column : second.column;
    if (!problem.message.empty()) return gcode::error_at(where, column, problem.message);
  }
  m.kind = MoveKind::arc;
  m.center_mm = centre;
  m.normal = gcode::plane_normal(state_.plane) * (clockwise ? -1.0 : 1.0);
  if (m.inverse_time) m.feed_mm_min = gcode::arc_length_mm(start, m) * m.inverse_time_per_min;
  return ok_status();
}

}  // namespace

Result<CanonicalProgram> interpret_gcode(std::string_view text, const std::string& source_name,
                                         const InterpretOptions& options) {
  std::optional<ToolTable> tools;
  if (!options.tool_table_path.empty()) {
    auto table = read_tool_table(options.tool_table_path);
    if (!table) return table.error();
    tools = std::move(table.value());
  }
  CanonicalProgram program;
  Interpreter interpreter(source_name, options, tools ? &*tools : nullptr);
  if (auto run = interpreter.run(text, program); !run) return run.error();
  return program;
}

}  // namespace pkm::program
