// Canned cycles as LinuxCNC 2.9's rs274 expands them (checked against its canonical calls, see
// tests/program/ngc_canned_cycle_test.cpp and scripts/regen-cycle-golden.sh).
//
// Geometry. Each cycle works in a plane-local frame (a, b: the two axes of the selected plane, c: its normal,
// the drilling axis): G17 (X, Y, Z), G18 (Z, X, Y), G19 (Y, Z, X). Per block:
//   - the series' initial level (LinuxCNC's "old Z") is the c coordinate where the first block of the series
//     found the tool; G98 retracts there (if above R), G99 to R;
//   - G91: X/Y (in-plane) words are steps repeated L times, R is relative to the initial level and the depth
//     relative to R; G90: L > 1 repeats the hole in place;
//   - if the initial level is below R, the tool first rapids along c up to R (and then the series behaves as
//   if
//     it had started at R: LinuxCNC does this again, a zero-length rapid, on every later block);
//   - before each hole: rapid in the plane at the current (first hole, if above R) or clear level, then
//     down to R;
//   - G73 pecks by Q with a chip-break rapid back up of 0.010 inch (0.254 mm); G83 pecks by Q, rapids out to
//     R and back down to 0.010 inch (0.254 mm) above the last depth (LinuxCNC's defaults);
//   - G87 back-bores: I J K are the offsets of the entry point along X Y Z in the plane, the normal one of
//   them
//     the top of the counterbore (absolute; in G91 relative to the bottom).
// Spindle and pauses go to the sink as events: "M5", "M3 S…", "M4 S…", "M0", and "M19" for LinuxCNC's
// ORIENT_SPINDLE (angle 0, G87).
//
// Approximated or deliberately different from rs274:
//   - G84 is floating-chuck tapping as LinuxCNC 2.9 emits it: feed down, M5, M4 (the reversal), dwell P
//     (0 when never given), feed out, M5, M3. LinuxCNC also disables the feed and spindle overrides around it
//     (DISABLE_FEED_OVERRIDE…); pkm has no overrides, so nothing is sent for them. The moves are plain feeds
//     at the programmed feed (no spindle synchronisation: rs274 emits none either).
//   - In G18 and G19, rs274 2.9 sends G84's two feeds to points whose coordinates are permuted (a bug in
//     LinuxCNC: the plane-local coordinates are passed in the wrong order). pkm reproduces those points so
//     that programs run as on LinuxCNC; CycleMemory::end_mm is where LinuxCNC then believes the tool is.
//   - LinuxCNC keeps G84's dwell P (and its G87 I J K) for the whole program; pkm's CycleMemory is reset when
//     a series ends, so a G84 without P in a later series dwells 0 s instead of the last P.
//   - A negative P is refused ("Negative p word used", LinuxCNC's text; 2.9 has that check disabled and
//     dwells a negative time). P-1 and Q-1, which rs274 reads as "no word" (its internal marker), are a
//     negative P and a non-positive Q here.
//   - CycleMemory keeps lengths in mm, so a G20/G21 inside a series keeps R and the depth where they were;
//     rs274 reuses the numbers in the new unit.
//   - Feed-rate, inverse-time and cutter-compensation checks belong to the executor.
#include "program/ngc_canned_cycle.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

namespace pkm::program::ngc {

namespace cycle_detail {

using gcode::Block;
using gcode::LineRef;

constexpr double kMmPerInch = 25.4;
constexpr double kPeckClearanceInch = 0.010;  // LinuxCNC's G73/G83 back-off, in either unit system
constexpr double kPeckClearanceMm = 0.254;
// pkm's bound on the moves one cycle block expands to (L holes times the pecks of each): LinuxCNC has none,
// so a huge L or a tiny Q made one block run for hours (or, with a Q too small to change the depth, for
// ever); a real program stays far below it.
constexpr double kMaxCycleMoves = 1'000'000;

/// Indices (0 = X, 1 = Y, 2 = Z) of the plane's first and second axes and of its normal.
struct Axes {
  int a, b, c;
};

Axes axes_of(Plane plane) {
  switch (plane) {
    case Plane::zx:
      return {2, 0, 1};
    case Plane::yz:
      return {1, 2, 0};
    case Plane::xy:
    default:
      return {0, 1, 2};
  }
}

char axis_letter(int axis) {
  return "XYZ"[axis];
}

/// Sends plane-local points (program units) to the sink as program coordinates in mm.
class Emitter {
 public:
  Emitter(CycleSink& sink, Axes axes, double unit_mm) : sink_(sink), axes_(axes), unit_mm_(unit_mm) {}
  Eigen::Vector3d point_mm(double a, double b, double c) const {
    Eigen::Vector3d p;
    p[axes_.a] = a * unit_mm_;
    p[axes_.b] = b * unit_mm_;
    p[axes_.c] = c * unit_mm_;
    return p;
  }
  void rapid(double a, double b, double c) { sink_.rapid(point_mm(a, b, c)); }
  void feed(double a, double b, double c) { sink_.feed(point_mm(a, b, c)); }
  void dwell(double seconds) { sink_.dwell(seconds); }
  void event(const std::string& what) { sink_.event(what); }

 private:
  CycleSink& sink_;
  Axes axes_;
  double unit_mm_;
};

/// One block's cycle, resolved to plane-local program units.
struct Hole {
  double r = 0.0;       ///< R plane
  double bottom = 0.0;  ///< depth
  double clear = 0.0;   ///< where each hole retracts to (G98: initial level if above R; G99: R)
  double dwell_s = 0.0;
  double peck = 0.0;  ///< Q
  double peck_clearance = 0.0;
  double offset_a = 0.0, offset_b = 0.0;  ///< G87 entry point relative to the hole
  double middle = 0.0;                    ///< G87 top of the counterbore
  std::string spindle_on;                 ///< "M3 S…" or "M4 S…": the spindle as it turns at the outset
};

std::string spindle_start(bool clockwise, double speed) {
  return fmt::format("M{} S{}", clockwise ? 3 : 4, speed);
}

// LinuxCNC 2.9 passes G84's plane-local point to its plane mapping as (b, c, a) in G18 and (c, a, b) in G19
// (see the file comment): the same permutation here gives rs274's points.
void tap_feed(Emitter& out, Plane plane, double a, double b, double c) {
  switch (plane) {
    case Plane::zx:
      out.feed(b, c, a);
      break;
    case Plane::yz:
      out.feed(c, a, b);
      break;
    case Plane::xy:
    default:
      out.feed(a, b, c);
  }
}

/// Pecks of one hole before the last feed to the bottom (LinuxCNC's loop counts them the same way).
double peck_count(const Hole& h) {
  return std::max(0.0, std::ceil((h.r - h.bottom) / h.peck) - 1.0);
}

void drill_pecks(Emitter& out, const Hole& h, double a, double b, bool out_to_r) {
  // The count bounds the loop too: far from the origin a small Q can leave `depth - peck` equal to `depth`.
  // One more than counted, so that the rounding of the repeated subtraction goes as in LinuxCNC.
  const double pecks = peck_count(h) + 1.0;
  double n = 0.0;
  for (double depth = h.r - h.peck; depth > h.bottom && n < pecks; depth -= h.peck, n += 1.0) {
    out.feed(a, b, depth);
    if (out_to_r) out.rapid(a, b, h.r);  // G83: clear the chips out of the hole
    out.rapid(a, b, depth + h.peck_clearance);
  }
  out.feed(a, b, h.bottom);
  out.rapid(a, b, h.clear);
}

void back_bore(Emitter& out, const Hole& h, double a, double b) {
  const double entry_a = a + h.offset_a, entry_b = b + h.offset_b;
  out.rapid(entry_a, entry_b, h.r);
  out.event("M5");
  out.event("M19");  // LinuxCNC orients the spindle (angle 0) so the tool passes through the hole
  out.rapid(entry_a, entry_b, h.bottom);
  out.rapid(a, b, h.bottom);
  out.event(h.spindle_on);
  out.feed(a, b, h.middle);
  out.feed(a, b, h.bottom);
  out.event("M5");
  out.event("M19");
  out.rapid(entry_a, entry_b, h.bottom);
  out.rapid(entry_a, entry_b, h.clear);
  out.rapid(a, b, h.clear);
  out.event(h.spindle_on);
}

/// The moves of one hole, the tool being at (a, b, R).
void hole_body(Emitter& out, int code, Plane plane, const Hole& h, double a, double b, double speed) {
  switch (code) {
    case 730:
    case 830:
      drill_pecks(out, h, a, b, code == 830);
      break;
    case 810:
    case 820:
      out.feed(a, b, h.bottom);
      if (code == 820) out.dwell(h.dwell_s);
      out.rapid(a, b, h.clear);
      break;
    case 840:
      tap_feed(out, plane, a, b, h.bottom);
      out.event("M5");
      out.event(spindle_start(false, speed));
      out.dwell(h.dwell_s);
      tap_feed(out, plane, a, b, h.clear);
      out.event("M5");
      out.event(spindle_start(true, speed));
      break;
    case 850:
    case 890:
      out.feed(a, b, h.bottom);
      if (code == 890) {
        out.dwell(h.dwell_s);
        out.feed(a, b, h.clear);
      } else {
        out.feed(a, b, h.r);
        out.rapid(a, b, h.clear);
      }
      break;
    case 860:
      out.feed(a, b, h.bottom);
      out.dwell(h.dwell_s);
      out.event("M5");
      out.rapid(a, b, h.clear);
      out.event(h.spindle_on);
      break;
    case 870:
      back_bore(out, h, a, b);
      break;
    case 880:
      out.feed(a, b, h.bottom);
      out.dwell(h.dwell_s);
      out.event("M5");
      out.event("M0");  // the operator retracts the spindle by hand
      out.event(h.spindle_on);
      break;
    default:
      break;
  }
}

/// Column of the cycle's G-code in the block, else of its first axis word: where an error about a word the
/// block lacks points.
int cycle_column(const Block& block) {
  if (block.g[gcode::g_motion].given()) return block.g[gcode::g_motion].column;
  const int axis = block.first_axis_column();
  return axis > 0 ? axis : 1;
}

/// Column of the first given of `letters`, else the cycle's column.
int word_column(const Block& block, std::initializer_list<char> letters) {
  for (char letter : letters)
    if (block[letter].given()) return block[letter].column;
  return cycle_column(block);
}

bool uses_dwell(int code) {
  return code == 820 || code == 840 || code == 860 || code == 880 || code == 890;
}

// Words a cycle block may not hold, checked as LinuxCNC checks a block before running it (texts of
// rs274 2.9).
Status check_words(const Block& block, const LineRef& where, int code) {
  const gcode::Value& l = block['L'];
  if (l.given()) {
    if (l.value < 0.0) return error_at(where, l.column, "Negative l word used");
    const double fraction = l.value - std::floor(l.value);
    if (fraction > 0.0001 && fraction <= 0.9999)
      return error_at(where, l.column, "Non integer value for integer");
  }
  const bool g4 = block.g[gcode::g_non_modal].is(40), g64 = block.g[gcode::g_path_control].is(640);
  const gcode::Value& p = block['P'];
  if (p.given() && !uses_dwell(code) && !g4 && !g64)
    return error_at(
        where, p.column,
        "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 M63 M64 "
        "M65 M66 M98 or user M code to use it");
  if (p.given() && p.value < 0.0) return error_at(where, p.column, "Negative p word used");
  const gcode::Value& q = block['Q'];
  if (q.given() && code != 730 && code != 830 && !g64)
    return error_at(
        where, q.column,
        "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses it");
  if (code != 870) {
    if (block['I'].given())
      return error_at(where, block['I'].column,
                      "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it");
    if (block['J'].given())
      return error_at(where, block['J'].column, "J word with no G2, G3, G5, G5.1, G10, G76 or G87 to use it");
    if (block['K'].given())
      return error_at(where, block['K'].column, "K word with no G2, G3, G33, G33.1, G76, or G87 to use it");
  }
  return ok_status();
}

/// The words of this cycle that may carry over from the previous block of the series, checked and resolved
/// (program units); `hole.r`, `hole.bottom` hold the R and depth words as written.
Status resolve_words(const Block& block, const LineRef& where, const CycleContext& context,
                     const CycleMemory& memory, bool same_cycle, Hole& hole, Eigen::Vector3d& ijk) {
  const double unit_mm = context.inch ? kMmPerInch : 1.0;
  const int code = context.code;
  const char code_text[] = {'g', char('0' + code / 100), char('0' + code / 10 % 10), '\0'};
  const gcode::Value& p = block['P'];
  if (code == 820 || code == 860 || code == 880 || code == 890) {
    if (!p.given() && !same_cycle)
      return error_at(where, cycle_column(block),
                      fmt::format("Dwell time p word missing with {}", code_text));
  }
  hole.dwell_s = p.given() ? p.value : (memory.has_p ? memory.p_s : 0.0);
  const gcode::Value& q = block['Q'];
  if (code == 730 || code == 830) {
    if (!q.given() && !same_cycle)
      return error_at(where, cycle_column(block), fmt::format("Q word missing with {}", code_text));
    hole.peck = q.given() ? q.value : memory.q_mm / unit_mm;
    if (hole.peck <= 0.0) return error_at(where, word_column(block, {'Q'}), "Negative or zero q value used");
  }
  if (code == 870) {
    const double remembered[3] = {memory.i_mm, memory.j_mm, memory.k_mm};
    for (int axis = 0; axis < 3; ++axis) {
      const char letter = char('I' + axis);
      if (!block[letter].given() && !same_cycle)
        return error_at(where, cycle_column(block), fmt::format("{} word missing with g87", letter));
      ijk[axis] = block[letter].given() ? block[letter].value : remembered[axis] / unit_mm;
    }
  }
  if ((code == 840 || code == 860 || code == 870 || code == 880) && !context.spindle_turning)
    return error_at(where, cycle_column(block),
                    code == 840 ? std::string("Spindle not turning in G84")
                                : fmt::format("Spindle not turning in {}", code_text));
  if (code == 840 && !context.spindle_clockwise)
    return error_at(where, cycle_column(block), "Spindle turning counterclockwise in G84");
  return ok_status();
}

const char* plane_name(const Axes& axes) {
  static const char* const by_normal[3] = {"yz", "xz", "xy"};
  return by_normal[axes.c];
}

/// The words a series must start with (R, the depth) and the repeat count; fills the values as written,
/// the left-out ones from the series (program units).
Status check_required(const Block& block, const LineRef& where, const CycleContext& context,
                      const CycleMemory& memory, bool same_cycle, double& r_written, double& depth_written,
                      int& repeats) {
  const double unit_mm = context.inch ? kMmPerInch : 1.0;
  const Axes axes = axes_of(context.plane);
  const gcode::Value& r_word = block['R'];
  if (!r_word.given() && !same_cycle)
    return error_at(where, cycle_column(block), "R clearance plane unspecified in cycle");
  const gcode::Value& l_word = block['L'];
  // Checked before the conversion to int, which a huge L would overflow.
  if (l_word.given() && l_word.value > kMaxCycleMoves)
    return error_at(where, l_word.column,
                    fmt::format("L repeat count above {} in cycle (pkm's bound)", kMaxCycleMoves));
  repeats = l_word.given() ? int(std::lround(l_word.value)) : 1;
  if (repeats == 0) return error_at(where, l_word.column, "Cannot do zero repeats of cycle");
  const char normal = axis_letter(axes.c);
  const gcode::Value& depth_word = block[normal];
  if (!depth_word.given() && !same_cycle)
    return error_at(where, cycle_column(block),
                    fmt::format("{} value unspecified in {} plane canned cycle", normal, plane_name(axes)));
  r_written = r_word.given() ? r_word.value : memory.r_mm / unit_mm;
  depth_written = depth_word.given() ? depth_word.value : memory.z_mm / unit_mm;
  return ok_status();
}

/// Refuses a block that would expand to more moves than kMaxCycleMoves or what is left of the program's
/// budget for cycles (at most 3 moves a peck, 14 steps a hole).
Status check_size(const Block& block, const LineRef& where, const CycleContext& context, int repeats,
                  const Hole& hole) {
  const bool pecking = context.code == 730 || context.code == 830;
  const double pecks = pecking ? peck_count(hole) : 0.0;
  const double budget = std::min(kMaxCycleMoves, double(context.max_moves));
  if (double(repeats) * (14.0 + 3.0 * pecks) <= budget) return ok_status();
  const std::string what =
      pecking ? fmt::format("{} holes of {} pecks", repeats, pecks) : fmt::format("{} holes", repeats);
  return error_at(where, pecking ? word_column(block, {'Q', 'L'}) : word_column(block, {'L'}),
                  fmt::format("{} in one cycle block: more than the {} moves left to it (pkm's bound: {} a "
                              "block, max_blocks for all the cycles of a program)",
                              what, budget, kMaxCycleMoves));
}

/// Where the holes of a block are, plane-local, program units.
struct Pattern {
  double a = 0.0, b = 0.0;            ///< G90: the hole; G91: where the tool is before the first step
  double step_a = 0.0, step_b = 0.0;  ///< G91: from hole to hole
  double from_a = 0.0, from_b = 0.0;  ///< where the tool is in the plane
  double current_c = 0.0;             ///< the tool's level
  double initial = 0.0;               ///< the series' initial level (G98)
  int repeats = 1;
  // G91 with polar words (XY plane): each hole adds to the distance from the origin and to the angle.
  double step_radius = 0.0;  ///< program units
  double step_angle_rad = 0.0;
};

// LinuxCNC's polar words in a cycle (XY plane): G90 `@` `^` place the hole (a word left out keeps the
// tool's own distance or angle), G91 steps them from hole to hole.
void locate_polar(const Block& block, const CycleContext& context, Pattern& pattern) {
  if (context.plane != Plane::xy || (!block.polar_radius.given() && !block.polar_angle.given())) return;
  constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
  if (context.incremental) {
    if (block.polar_radius.given()) pattern.step_radius = block.polar_radius.value;
    if (block.polar_angle.given()) pattern.step_angle_rad = block.polar_angle.value * kRadPerDeg;
    return;
  }
  const double radius =
      block.polar_radius.given() ? block.polar_radius.value : std::hypot(pattern.b, pattern.a);
  const double angle =
      block.polar_angle.given() ? block.polar_angle.value * kRadPerDeg : std::atan2(pattern.b, pattern.a);
  pattern.a = radius * std::cos(angle);
  pattern.b = radius * std::sin(angle);
}

// One G91 polar step from the hole before (LinuxCNC: the distance first, then the angle).
void step_polar(Pattern& pattern) {
  if (pattern.step_radius != 0.0) {
    const double radius = std::hypot(pattern.b, pattern.a) + pattern.step_radius;
    const double angle = std::atan2(pattern.b, pattern.a);
    pattern.a = radius * std::cos(angle);
    pattern.b = radius * std::sin(angle);
  }
  if (pattern.step_angle_rad != 0.0) {
    const double radius = std::hypot(pattern.b, pattern.a);
    const double angle = std::atan2(pattern.b, pattern.a) + pattern.step_angle_rad;
    pattern.a = radius * std::cos(angle);
    pattern.b = radius * std::sin(angle);
  }
}

// G91: in-plane words are steps, R is relative to the series' initial level, the depth relative to R.
void locate(const Block& block, const CycleContext& context, const CycleMemory& memory, double r_written,
            double depth_written, Pattern& pattern, Hole& hole) {
  const double unit_mm = context.inch ? kMmPerInch : 1.0;
  const Axes axes = axes_of(context.plane);
  const Eigen::Vector3d position = context.position_mm / unit_mm;
  pattern.current_c = position[axes.c];
  // The initial level is where the series began, whatever the later blocks of the series found.
  pattern.initial = memory.started ? memory.old_z_mm / unit_mm : pattern.current_c;
  pattern.a = pattern.from_a = position[axes.a];
  pattern.b = pattern.from_b = position[axes.b];
  const gcode::Value& word_a = block[axis_letter(axes.a)];
  const gcode::Value& word_b = block[axis_letter(axes.b)];
  if (context.incremental) {
    pattern.step_a = word_a.given() ? word_a.value : 0.0;
    pattern.step_b = word_b.given() ? word_b.value : 0.0;
    hole.r = r_written + pattern.initial;
    hole.bottom = hole.r + depth_written;
  } else {
    hole.r = r_written;
    hole.bottom = depth_written;
    if (word_a.given()) pattern.a = word_a.value;
    if (word_b.given()) pattern.b = word_b.value;
  }
  locate_polar(block, context, pattern);
}

/// All the moves of the block; leaves in `pattern` the last hole.
void drill(Emitter& out, const CycleContext& context, Pattern& pattern, Hole& hole) {
  if (pattern.initial < hole.r) {  // below the R plane: straight up to it first
    out.rapid(pattern.from_a, pattern.from_b, hole.r);
    pattern.initial = hole.r;
    pattern.current_c = hole.r;
  }
  hole.clear = context.retract_to_r ? hole.r : pattern.initial;
  for (int n = 0; n < pattern.repeats; ++n) {
    pattern.a += pattern.step_a;
    pattern.b += pattern.step_b;
    step_polar(pattern);
    if (n == 0 && pattern.current_c > hole.r) {  // from where the tool is, over the hole, down to R
      out.rapid(pattern.a, pattern.b, pattern.current_c);
      out.rapid(pattern.a, pattern.b, hole.r);
    } else {  // from hole to hole at the clear level
      out.rapid(pattern.a, pattern.b, hole.clear);
      if (hole.clear > hole.r) out.rapid(pattern.a, pattern.b, hole.r);
    }
    hole_body(out, context.code, context.plane, hole, pattern.a, pattern.b, context.spindle_speed);
  }
}

/// What the next block of the series may leave out, in mm and seconds.
void remember(const Block& block, const CycleContext& context, double r_written, double depth_written,
              const Hole& hole, const Eigen::Vector3d& ijk, CycleMemory& memory) {
  const double unit_mm = context.inch ? kMmPerInch : 1.0;
  const int code = context.code;
  memory.started = true;
  memory.code = code;
  memory.r_mm = r_written * unit_mm;
  memory.z_mm = depth_written * unit_mm;
  memory.has_r = memory.has_z = true;
  if (block['P'].given() && uses_dwell(code)) {
    memory.p_s = hole.dwell_s;
    memory.has_p = true;
  }
  if (code == 730 || code == 830) {
    memory.q_mm = hole.peck * unit_mm;
    memory.has_q = true;
  }
  if (code == 870) {
    memory.i_mm = ijk[0] * unit_mm;
    memory.j_mm = ijk[1] * unit_mm;
    memory.k_mm = ijk[2] * unit_mm;
    memory.has_ijk = true;
  }
}

}  // namespace cycle_detail

Status run_canned_cycle(const gcode::Block& block, const gcode::LineRef& where, const CycleContext& context,
                        CycleMemory& memory, CycleSink& sink) {
  using namespace cycle_detail;  // here only: the library is built in unity batches
  if (Status s = check_words(block, where, context.code); !s) return s;
  // R, the depth, P, Q and I J K carry over only while the same cycle repeats (LinuxCNC's motion mode).
  const bool same_cycle = memory.started && memory.code == context.code;
  double r_written = 0.0, depth_written = 0.0;
  Pattern pattern;
  if (Status s = check_required(block, where, context, memory, same_cycle, r_written, depth_written,
                                pattern.repeats);
      !s)
    return s;
  Hole hole;
  locate(block, context, memory, r_written, depth_written, pattern, hole);
  const Axes axes = axes_of(context.plane);
  const char normal = axis_letter(axes.c);
  if (hole.r < hole.bottom)
    return error_at(
        where, word_column(block, {'R', normal}),
        fmt::format("R less than {} in cycle in {} plane", char(normal - 'A' + 'a'), plane_name(axes)));
  Eigen::Vector3d ijk = Eigen::Vector3d::Zero();
  if (Status s = resolve_words(block, where, context, memory, same_cycle, hole, ijk); !s) return s;
  hole.peck_clearance = context.inch ? kPeckClearanceInch : kPeckClearanceMm;
  if (Status s = check_size(block, where, context, pattern.repeats, hole); !s) return s;
  hole.offset_a = ijk[axes.a];
  hole.offset_b = ijk[axes.b];
  hole.middle = context.incremental ? hole.bottom + ijk[axes.c] : ijk[axes.c];  // K: absolute, or from bottom
  hole.spindle_on = spindle_start(context.spindle_clockwise, context.spindle_speed);

  const double unit_mm = context.inch ? kMmPerInch : 1.0;
  memory.old_z_mm = pattern.initial * unit_mm;  // the series' level stays, even when raised to R in drill()
  Emitter out(sink, axes, unit_mm);
  drill(out, context, pattern, hole);
  remember(block, context, r_written, depth_written, hole, ijk, memory);
  memory.end_mm = out.point_mm(pattern.a, pattern.b, hole.clear);
  return ok_status();
}

}  // namespace pkm::program::ngc
