#pragma once
// One block (line) of G-code sorted by meaning: its G- and M-codes by modal group, and the value of every
// other letter. Building it rejects what no block may hold whatever the modal state: unknown or unsupported
// codes, two codes of one modal group, a letter given twice, letters pkm does not support (U V W E).
#include <array>

#include "program/gcode_lexer.hpp"

namespace pkm::program::gcode {

/// A G- or M-code: its number times ten (G90.1 → 901, G1 → 10) and where it was written.
struct Code {
  int number = -1;  ///< ×10; -1 = not in this block
  int column = 0;
  bool given() const { return number >= 0; }
  bool is(int g_times_ten) const { return number == g_times_ten; }
};

/// The value of a letter (X, F, P, ...) in this block.
struct Value {
  double value = 0.0;
  int column = 0;  ///< 0 = not in this block
  bool given() const { return column > 0; }
};

/// Modal groups of the G-codes pkm accepts (RS274/NGC numbering in comments).
enum GGroup : int {
  g_non_modal,     // 0: G4 G10 G28 G28.1 G30 G30.1 G52 G53 G92 G92.1 G92.2 G92.3
  g_motion,        // 1: G0 G1 G2 G3 G33 G33.1 G38.2–G38.5 G73 G80–G89
  g_plane,         // 2: G17 G18 G19
  g_distance,      // 3: G90 G91
  g_arc_distance,  // 4: G90.1 G91.1
  g_feed_mode,     // 5: G93 G94 G95
  g_units,         // 6: G20 G21
  g_cutter,        // 7: G40 G41 G41.1 G42 G42.1
  g_tool_length,   // 8: G43 G43.1 G43.2 G49
  g_retract,       // 10: G98 G99
  g_coordinates,   // 12: G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3
  g_path_control,  // 13: G61 G61.1 G64
  g_spindle_mode,  // 14: G96 G97
  g_lathe,         // 15: G7 G8
  g_group_count
};

/// Modal groups of the M-codes pkm accepts.
enum MGroup : int {
  m_stop,         // 4: M0 M1 M2 M30 M60
  m_io,           // 5: M62–M68
  m_tool_change,  // 6: M6 M61
  m_spindle,      // 7: M3 M4 M5 M19
  m_coolant,      // 8: M7 M8 M9
  m_override,     // 9: M48–M53
  m_state,        // 10: M70–M73
  m_user,         // 10: M100–M199
  m_group_count
};

struct Block {
  std::array<Code, g_group_count> g;
  std::array<Code, m_group_count> m;
  std::array<Value, 26> letters;  ///< indexed by letter − 'A'; G and M are not stored here
  Value polar_radius;             ///< `@`: LinuxCNC's polar distance in the XY plane
  Value polar_angle;              ///< `^`: LinuxCNC's polar angle in degrees

  const Value& operator[](char letter) const { return letters[static_cast<std::size_t>(letter - 'A')]; }
  /// Column of the first of X Y Z A B C @ ^ in this block, or 0.
  int first_axis_column() const;
};

/// Sorts the words of a lexed line into `out` (overwritten).
Status build_block(const LexedLine& line, const LineRef& where, Block& out);

/// "G90.1", "M6": a code's name for messages.
std::string code_name(char letter, int number_times_ten);

}  // namespace pkm::program::gcode
