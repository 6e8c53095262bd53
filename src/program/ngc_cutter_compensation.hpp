#pragma once
// Cutter radius compensation (G40, G41/G42 with D, G41.1/G42.1) as LinuxCNC 2.9 does it: every move of the
// programmed (nominal) path goes through this stage, which emits the moves of the tool centre. With
// compensation on, a move's end depends on the next move (a concave corner ends at the intersection of the
// two offset paths, a convex one gets an arc around the corner), so moves wait in a queue until the next
// one is known; entry and exit moves, too-small arcs and gouges behave and fail as in rs274.
//
// Contract:
//   - Moves in and out are CanonicalMoves in program coordinates, mm (kind rapid, line, arc or dwell); every
//     field except the geometry (line, feed, tool length, path control …) is kept from the programmed move
//     each output move comes from. Dwells wait in the queue in their place.
//   - With compensation off and the queue empty, a move passes through unchanged.
//   - Errors carry file:line:column and LinuxCNC's reason ("cutter gouging", "radius of cutter
//     compensation entry arc too small" …).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/result.hpp"
#include "program/canonical_program.hpp"
#include "program/gcode_lexer.hpp"

namespace pkm::program::ngc {

enum class CompensationSide { left, right };  ///< G41 / G42: the tool on the left / right of the path

class CutterCompensation {
 public:
  CutterCompensation();
  ~CutterCompensation();
  CutterCompensation(CutterCompensation&&) noexcept;
  CutterCompensation& operator=(CutterCompensation&&) noexcept;

  /// Where the tool is before the first move (program coordinates, mm).
  void set_position(const Eigen::Vector3d& position_mm);
  /// Program units (G20: true). rs274 keeps a few tolerances in program units without converting them (the
  /// overrun allowed on an arc whose end a concave corner moves: 0.001 rad in G20, 0.0254 rad in G21).
  void set_inch(bool inch);
  /// G41/G42 (radius from the tool table's D) or G41.1/G42.1: the next move is the entry move. `column`
  /// points at the G-code for errors (compensation in a plane other than G17/G18, already on …).
  Status start(CompensationSide side, double radius_mm, Plane plane, const gcode::LineRef& where, int column);
  /// G17/G18/G19 (added): rs274 refuses a change of plane while compensation is on.
  Status select_plane(Plane plane, const gcode::LineRef& where, int column);
  /// G40: the next move is the exit move. As in rs274, the queued moves end where they are (checked as at a
  /// corner; they come out with the next move() or flush()), and the exit move goes straight from there to
  /// its programmed end: an arc is refused.
  Status stop(const gcode::LineRef& where, int column);
  bool active() const;
  /// A programmed move; what can be emitted is appended to `out`.
  Status move(const CanonicalMove& programmed, const gcode::LineRef& where, std::vector<CanonicalMove>& out);
  /// The same, errors pointing at `column` (the motion word) instead of the block's first column.
  Status move(const CanonicalMove& programmed, const gcode::LineRef& where, int column,
              std::vector<CanonicalMove>& out);
  /// Emits everything queued (end of program, or an operation that cannot wait, as in rs274: M0 M1 M2 M30
  /// M60). Compensation stays on: after M0 the next corner can no longer move those ends (rs274 does the
  /// same).
  Status flush(std::vector<CanonicalMove>& out);
  /// The same, errors (a queued move that can no longer reach its end) reported at `where`:`column`
  /// (flush(out) reports them on the last move's line).
  Status flush(std::vector<CanonicalMove>& out, const gcode::LineRef& where, int column);
  /// Where the tool centre is after everything emitted and queued (after G40: the last compensated end).
  Eigen::Vector3d tool_position_mm() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::program::ngc
