#pragma once
// The canonical moves a part program means, whatever language it was written in (G-code or APT CL data).
// Interpreters produce them; the path builder consumes them. Every move keeps the source line it came from,
// so that any later problem (an unreachable pose, a limit) can be reported against the program text.
//
// Units: millimetres, degrees, minutes for feed (mm/min), seconds for dwell. Programs in inches are converted
// at interpretation. Coordinates are work coordinates: the tool tip in the machine's work frame. A G-code
// program's own coordinates (the ones LinuxCNC's canonical interface reports, after G43 tool length offsets)
// differ from them by the work offsets in effect (G54–G59.3 with their XY rotation, G92): each move names
// its WorkFrame, and program_coordinates() gives the program's numbers back (see docs/part-programs.md).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace pkm::program {

enum class MoveKind { rapid, line, arc, dwell };

/// A principal plane of G17/G18/G19, named by its normal axis.
enum class Plane { xy, zx, yz };

/// Orientation of the tool as the program states it.
///  - `abc`: fixed-axis angles A, B, C in degrees, R = Rz(C)·Ry(B)·Rx(A), whatever convention the machine
///  file
///    uses for its own poses (for planar machines C is the platform angle φ).
///  - `tool_axis`: a unit tool-axis vector (APT convention: from the tool tip towards the spindle); the spin
///    about it is left free.
enum class OrientationSource { abc, tool_axis };

/// The work offsets in effect for a move: work = g5x + Rz(xy_rotation)·(program + g92), angles added.
struct WorkFrame {
  Eigen::Vector3d g5x_mm = Eigen::Vector3d::Zero();  ///< G54–G59.3 offset of the active system
  Eigen::Vector3d g5x_abc_deg = Eigen::Vector3d::Zero();
  double xy_rotation_deg = 0.0;  ///< G10 L2 R of the active system
  Eigen::Vector3d g92_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92_abc_deg = Eigen::Vector3d::Zero();
  int system = 1;  ///< 1 = G54 … 9 = G59.3
  bool identity() const {
    return g5x_mm.isZero(0.0) && g5x_abc_deg.isZero(0.0) && xy_rotation_deg == 0.0 && g92_mm.isZero(0.0) &&
           g92_abc_deg.isZero(0.0);
  }
};

struct CanonicalMove {
  int line = 0;  ///< 1-based line of the main program (for a move inside a subroutine, the calling line)
  int source_file = 0;  ///< index into CanonicalProgram::files of the file the move was written in
  int source_line = 0;  ///< line in that file (= line for a move written in the main program's own flow)
  int frame = 0;        ///< index into CanonicalProgram::frames
  MoveKind kind = MoveKind::line;
  Eigen::Vector3d end_mm = Eigen::Vector3d::Zero();  ///< end point of the tool tip (dwell: where it dwells)
  Eigen::Vector3d end_abc_deg = Eigen::Vector3d::Zero();  ///< A, B, C at the end
  OrientationSource orientation = OrientationSource::abc;
  Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();  ///< used when orientation == tool_axis
  // Arcs and helices (kind == arc); the start is the previous move's end.
  Eigen::Vector3d center_mm = Eigen::Vector3d::Zero();  ///< centre in the arc plane, at the start's height
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit axis; the motion is counter-clockwise about it
  int turns = 1;  ///< 1: less than or one full turn; k: k − 1 further full turns (G2/G3 P word)
  Plane plane = Plane::xy;
  // Feed (kind == line or arc). Rapids move at the machine's rapid speed.
  double feed_mm_min = 0.0;             ///< programmed feed (G94 units per minute, in mm/min)
  double feed_per_revolution_mm = 0.0;  ///< G95 feed (mm per spindle turn); feed_mm_min is it × S
  bool inverse_time = false;            ///< G93: the move takes 1/inverse_time_per_min minutes
  double inverse_time_per_min = 0.0;
  double dwell_s = 0.0;         ///< kind == dwell
  double tool_length_mm = 0.0;  ///< active G43 tool length offset (0 after G49)
  // Path control mode in effect (G-code G61/G61.1/G64; added for the planner). G61 and G61.1 stop at the
  // end of the move; G64 blends, within path_tolerance_mm of the corner when G64 P gave one.
  double path_tolerance_mm = -1.0;  ///< G64 P tolerance in mm; -1 = none given (G64 or G64 P0: no limit)
  bool exact_stop = false;          ///< G61 / G61.1: come to a stop at the end of this move
  bool probe = false;               ///< G38.2–G38.5: a probing move (offline: to its target, no contact)
  /// A move the program does not make and LinuxCNC leaves to the operator: the retraction to the clear plane
  /// after G88 (and G84 outside G17), which pkm plans so that the path stays continuous.
  bool inserted = false;
};

/// Non-motion events, recorded with their line so reports can show them (tool change, spindle, coolant).
struct ProgramEvent {
  int line = 0;      ///< main program line (the calling line inside a subroutine)
  std::string what;  ///< e.g. "M6 T3", "M3 S12000", "M5"
  int source_file = 0;
  int source_line = 0;
};

struct CanonicalProgram {
  std::string source;                             ///< file the program came from
  std::string format;                             ///< how it was read: "G-code (RS274/NGC)", "NX CLSF" …
  std::vector<std::string> files;                 ///< [0] = source, then the subroutine files that were read
  std::vector<WorkFrame> frames = {WorkFrame{}};  ///< [0] = no offsets
  std::vector<CanonicalMove> moves;
  std::vector<ProgramEvent> events;
  Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();  ///< where the interpreter assumed the tool starts
  Eigen::Vector3d start_abc_deg = Eigen::Vector3d::Zero();
  int end_line = 0;                ///< line of M2/M30/END, or the last line
  std::vector<std::string> notes;  ///< what the user should know about how the program was read
};

/// A move's end, centre and arc axis as the program wrote them (before its work frame); angles likewise.
struct ProgramCoordinates {
  Eigen::Vector3d end_mm;
  Eigen::Vector3d center_mm;
  Eigen::Vector3d end_abc_deg;
};
ProgramCoordinates program_coordinates(const CanonicalProgram& program, const CanonicalMove& move);

}  // namespace pkm::program
