#pragma once
// Writing canonical moves as G-code: the inverse of interpret_gcode. The text is RS274/NGC as LinuxCNC reads
// it, and interpret_gcode reads it back into the same moves (to the decimals written): kind, end point and
// A B C, arc centre, direction, plane and turns, feed or inverse-time feed, dwell, path control mode, and the
// program's events in their place among the moves.
//
// The program is absolute and explicit, so that it means the same whatever state a controller starts in: a
// preamble sets every modal group the moves rely on (G17 G21 G90 G94 G91.1 G40 G49 G64), and every motion
// line carries all of X Y Z A B C. Modal words (plane, G93/G94, G61/G64, F) are written only when they
// change.
#include <string>
#include <vector>

#include "core/result.hpp"
#include "program/canonical_program.hpp"

namespace pkm::program {

struct GcodeWriteOptions {
  /// Written first, each as a comment line "(text)"; parentheses are removed from the text (G-code comments
  /// do not nest) and each line of a multi-line text becomes its own comment.
  std::vector<std::string> header_comments;
  /// Digits after the point of lengths (X Y Z, I J K, G64 P) and of feeds in mm/min, 0 to 12.
  int decimals_mm = 4;
  /// Digits after the point of A B C, 0 to 12.
  int decimals_deg = 4;
  /// Append "(src N)" to each move's and event's line, N being its line in the program it was read from.
  bool write_source_lines = true;
};

/// The G-code for `program`, lines ending in '\n'.
///
///  - Rapids, lines, arcs: G0 / G1 / G2 (clockwise) or G3 about the arc's normal, which must be ±X, ±Y or ±Z
///    (G19, G18, G17); I J K incremental from the start (G91.1), P for more than one turn; the end off the
///    plane makes a helix. Arcs whose start is not exactly on the circle (spirals) are written as they are
///    when the reading interpreter's radius tolerance (G21) still accepts them after rounding.
///  - Feeds: F in mm/min (G94), or G93 and F = inverse_time_per_min on every inverse-time move. Inverse-time
///    F and dwell seconds (G4 P) are written exactly (the shortest decimal that reads back the same double).
///  - Events (ProgramEvent) are written before the first move whose line is the event's line or later: in a
///    block, LinuxCNC acts on M and T words before it moves. Events that are not G-code (CL data's
///    "LOADTL/3", "PPRINT ...") are written as comments; they have no G-code meaning pkm could check.
///  - The program starts from wherever the reading interpreter assumes (program.start_mm / start_abc_deg
///    are not written): the first move's end is absolute, its arc centre is relative to program.start_mm.
///  - M2 ends it.
///
/// Errors name the source and line of the move: a tool-axis orientation (OrientationSource::tool_axis; G-code
/// states A B C), a tool length offset (tool_length_mm != 0: not supported, as the offset would have to be
/// re-expressed for G43), an arc whose normal is not a coordinate axis, an arc that rounding would turn into
/// a different arc (a tiny arc becoming a full circle, an end pushed off the circle beyond the tolerance), a
/// feed move without a feed, a value that is not finite. Bad options are ErrorCode::bad_input.
Result<std::string> write_gcode(const CanonicalProgram& program, const GcodeWriteOptions& options);

}  // namespace pkm::program
