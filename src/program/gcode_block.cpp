#include "program/gcode_block.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace pkm::program::gcode {

namespace {

constexpr int kUnsupported = -1;
constexpr int kUnknown = -2;

struct Classified {
  int group;           ///< a GGroup / MGroup, or kUnsupported / kUnknown
  const char* reason;  ///< for unsupported codes: what the code does
};

bool in(int n, int lo, int hi) {
  return n >= lo && n <= hi;
}

// G-codes by modal group; the ones pkm knows but does not carry out name what they do, so the message says
// why.
Classified classify_g(int n) {
  switch (n) {
    case 40:
    case 100:
    case 280:
    case 281:
    case 300:
    case 301:
    case 520:
    case 530:
    case 920:
    case 921:
    case 922:
    case 923:
      return {g_non_modal, nullptr};
    case 0:
    case 10:
    case 20:
    case 30:
    case 382:
    case 383:
    case 384:
    case 385:
    case 730:
    case 800:
    case 810:
    case 820:
    case 830:
    case 840:
    case 850:
    case 860:
    case 870:
    case 880:
    case 890:
      return {g_motion, nullptr};
    case 170:
    case 180:
    case 190:
      return {g_plane, nullptr};
    case 200:
    case 210:
      return {g_units, nullptr};
    case 400:
    case 410:
    case 411:
    case 420:
    case 421:
      return {g_cutter, nullptr};
    case 430:
    case 431:
    case 432:
    case 490:
      return {g_tool_length, nullptr};
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 591:
    case 592:
    case 593:
      return {g_coordinates, nullptr};
    case 610:
    case 611:
    case 640:
      return {g_path_control, nullptr};
    case 900:
    case 910:
      return {g_distance, nullptr};
    case 901:
    case 911:
      return {g_arc_distance, nullptr};
    case 930:
    case 940:
    case 950:
      return {g_feed_mode, nullptr};
    case 960:
    case 970:
      return {g_spindle_mode, nullptr};
    case 980:
    case 990:
      return {g_retract, nullptr};
    case 80:
      return {g_lathe, nullptr};
    default:
      break;
  }
  if (in(n, 50, 53)) return {kUnsupported, "spline or NURBS motion"};
  if (n == 70) return {kUnsupported, "lathe diameter mode"};
  if (n == 150 || n == 160) return {kUnsupported, "polar coordinates"};
  if (n == 171 || n == 181 || n == 191) return {kUnsupported, "UVW plane"};
  if (n == 330 || n == 331) return {kUnsupported, "spindle-synchronized motion"};
  if (n == 500 || n == 510) return {kUnsupported, "scaling"};
  if (n == 680 || n == 690) return {kUnsupported, "coordinate system rotation"};
  if (n == 700 || n == 710 || n == 720) return {kUnsupported, "lathe cycle"};
  if (n == 740 || n == 760) return {kUnsupported, "lathe tapping or threading cycle"};
  return {kUnknown, nullptr};
}

Classified classify_m(int n) {
  switch (n) {
    case 0:
    case 10:
    case 20:
    case 300:
    case 600:
      return {m_stop, nullptr};
    case 60:
    case 610:
      return {m_tool_change, nullptr};
    case 30:
    case 40:
    case 50:
    case 190:
      return {m_spindle, nullptr};
    case 70:
    case 80:
    case 90:
      return {m_coolant, nullptr};
    default:
      break;
  }
  if (in(n, 480, 530)) return {m_override, nullptr};
  if (in(n, 620, 680)) return {m_io, nullptr};
  if (in(n, 700, 730)) return {m_state, nullptr};
  if (in(n, 1000, 1990)) return {m_user, nullptr};
  if (n == 980 || n == 990) return {kUnsupported, "Fanuc-style subprogram call"};
  return {kUnknown, nullptr};
}

// What pkm says about letters it does not accept at all.
const char* unsupported_letter(char letter) {
  switch (letter) {
    case 'U':
    case 'V':
    case 'W':
      return "axis is not supported (axes are X Y Z A B C)";
    case 'E':
      return "word is not supported (lathe threading)";
    default:
      return nullptr;
  }
}

}  // namespace

std::string code_name(char letter, int number_times_ten) {
  if (number_times_ten % 10 == 0) return fmt::format("{}{}", letter, number_times_ten / 10);
  return fmt::format("{}{}.{}", letter, number_times_ten / 10, number_times_ten % 10);
}

int Block::first_axis_column() const {
  int column = 0;
  for (const char axis : {'X', 'Y', 'Z', 'A', 'B', 'C'}) {
    const int c = (*this)[axis].column;
    if (c > 0 && (column == 0 || c < column)) column = c;
  }
  for (const Value* polar : {&polar_radius, &polar_angle})
    if (polar->column > 0 && (column == 0 || polar->column < column)) column = polar->column;
  return column;
}

Status build_block(const LexedLine& line, const LineRef& where, Block& out) {
  out.g.fill(Code{});
  out.m.fill(Code{});
  out.letters.fill(Value{});
  out.polar_radius = Value{};
  out.polar_angle = Value{};
  for (const Word& word : line.words) {
    if (word.letter == 'G' || word.letter == 'M') {
      const bool is_g = word.letter == 'G';
      // Codes go up to M199 / G99.x; anything larger is a bad number (and would not fit the rounding below).
      const bool in_range = word.value >= 0.0 && word.value < 1000.0;
      const double tenths = word.value * 10.0;
      const long rounded = in_range ? std::lround(tenths) : -1;
      if (!in_range || std::abs(tenths - static_cast<double>(rounded)) > 1e-6 || (!is_g && rounded % 10 != 0))
        return error_at(where, word.column,
                        fmt::format("bad {}-code number {}{}", word.letter, word.letter, word.value));
      const int number = static_cast<int>(rounded);
      const Classified kind = is_g ? classify_g(number) : classify_m(number);
      if (kind.group == kUnknown)
        return error_at(where, word.column,
                        fmt::format("unknown {}-code {}", word.letter, code_name(word.letter, number)));
      if (kind.group == kUnsupported)
        return error_at(where, word.column,
                        fmt::format("unsupported {}-code {} ({})", word.letter,
                                    code_name(word.letter, number), kind.reason));
      Code& slot =
          is_g ? out.g[static_cast<std::size_t>(kind.group)] : out.m[static_cast<std::size_t>(kind.group)];
      if (is_g && kind.group == g_motion && slot.given() && (number == 800 || slot.number == 800)) {
        // rs274 accepts G80 beside another motion code (the Fanuc-style safety line `G0 G80`): the other
        // code is the motion mode, the cycle being cancelled either way.
        if (slot.number == 800) slot = Code{number, word.column};
        continue;
      }
      if (slot.given())
        return error_at(where, word.column,
                        fmt::format("{} and {} in one block belong to the same modal group",
                                    code_name(word.letter, slot.number), code_name(word.letter, number)));
      slot = Code{number, word.column};
      continue;
    }
    if (const char* why = unsupported_letter(word.letter))
      return error_at(where, word.column, fmt::format("{} {}", word.letter, why));
    const bool polar = word.letter == '@' || word.letter == '^';
    if (!polar && (word.letter < 'A' || word.letter > 'Z'))
      return error_at(where, word.column, fmt::format("unexpected character '{}'", word.letter));
    Value& slot = word.letter == '@'   ? out.polar_radius
                  : word.letter == '^' ? out.polar_angle
                                       : out.letters[static_cast<std::size_t>(word.letter - 'A')];
    if (slot.given())
      return error_at(where, word.column, fmt::format("two {} words in one block", word.letter));
    slot = Value{word.value, word.column};
  }
  return ok_status();
}

}  // namespace pkm::program::gcode
