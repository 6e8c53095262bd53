#pragma once
// Canned cycles G73 and G81–G89 (with G98/G99, L repeats and incremental mode) expanded into the rapids,
// feeds, dwells and spindle events LinuxCNC's rs274 produces for them, in the same order and to the same
// points. The executor (gcode_interpreter.cpp) calls run_canned_cycle for every block executed while a cycle
// is the motion mode and the block has axis words (or is the block that names the cycle).
//
// Contract:
//   - Block values are in program units (inch after G20); `context.inch` says which. Points given to the
//     sink are program coordinates in mm (the same coordinates rs274 prints, converted to mm).
//   - Errors carry file:line:column of the offending word (missing R, Z or P; negative L; R below Z; Q ≤ 0
//     for G73/G83 …), with LinuxCNC's reasons; and pkm's bound on the moves of a block (L holes times the
//     pecks of each: at most a million, and no more than `max_moves`).
//   - CycleMemory holds what LinuxCNC keeps between the blocks of one series of cycles (the Z to retract to
//     for G98, the sticky R/Z/Q/P …). The executor resets it to CycleMemory{} when the motion mode leaves
//     the cycles (G80, G0–G3 …), so the next cycle block starts a new series.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "core/result.hpp"
#include "program/canonical_program.hpp"
#include "program/gcode_block.hpp"

namespace pkm::program::ngc {

/// What a cycle does, in order.
class CycleSink {
 public:
  virtual ~CycleSink() = default;
  virtual void rapid(const Eigen::Vector3d& to_mm) = 0;
  virtual void feed(const Eigen::Vector3d& to_mm) = 0;
  virtual void dwell(double seconds) = 0;
  /// Spindle and pause events, named as the executor names its events: "M5", "M3 S500", "M4 S500", "M0".
  virtual void event(const std::string& what) = 0;
};

struct CycleContext {
  int code = 810;  ///< the cycle's G-code ×10: 730, 810, 820, … 890
  Plane plane = Plane::xy;
  bool retract_to_r = false;  ///< G99 (false: G98, back to the Z the series started from)
  bool incremental = false;   ///< G91
  bool inch = false;          ///< G20: block values are inches
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  ///< where the tool is (program coordinates)
  double spindle_speed = 0.0;  ///< S in effect (G84/G74-style tapping restarts the spindle with it)
  bool spindle_clockwise = true;
  bool spindle_turning = true;  ///< false after M5: G84, G86, G87 and G88 refuse to run (LinuxCNC does)
  /// Moves the block may still make (the executor's budget for all the cycles of a program, max_blocks):
  /// one block can expand to millions of moves (L, Q), which no count of blocks would otherwise bound.
  std::uint64_t max_moves = UINT64_MAX;
};

/// LinuxCNC's memory between the blocks of one series of cycles; run_canned_cycle reads and updates it.
struct CycleMemory {
  bool started = false;   ///< false: this block starts a series (the executor resets it)
  double old_z_mm = 0.0;  ///< the plane-normal coordinate before the series (G98), mm
  double r_mm = 0.0, z_mm = 0.0, q_mm = 0.0, p_s = 0.0;  ///< sticky words, mm / seconds
  bool has_r = false, has_z = false, has_q = false, has_p = false;
  double i_mm = 0.0, j_mm = 0.0, k_mm = 0.0;  ///< G87 back-boring offsets
  bool has_ijk = false;
  /// The cycle of the previous block of the series (LinuxCNC's motion mode): R, Z, P, Q and I J K may be
  /// left out only when the block repeats that cycle; 0 before the first block.
  int code = 0;
  /// Where LinuxCNC takes the tool to be after the block: at the clear plane above the last hole. That is the
  /// last point sent to the sink except after G88 (the operator retracts by hand) and G84 outside G17 (see
  /// ngc_canned_cycle.cpp); the executor continues from here, as rs274 does.
  Eigen::Vector3d end_mm = Eigen::Vector3d::Zero();
};

Status run_canned_cycle(const gcode::Block& block, const gcode::LineRef& where, const CycleContext& context,
                        CycleMemory& memory, CycleSink& sink);

}  // namespace pkm::program::ngc
