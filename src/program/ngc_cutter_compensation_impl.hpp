#pragma once
// Private state of CutterCompensation, shared by its translation units (queue handling, straight moves,
// arcs). All geometry works in the compensation plane's (first, second) frame as rs274 does: (X, Y) for G17,
// (Z, X) for G18; the third coordinate (along the plane normal) only rides along.
#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "core/units.hpp"
#include "program/canonical_program.hpp"
#include "program/gcode_arc.hpp"
#include "program/gcode_lexer.hpp"
#include "program/ngc_cutter_compensation.hpp"

namespace pkm::program::ngc {

/// rs274's TOLERANCE_CONCAVE_CORNER (rad): corners within it of straight on (or, for some, of a full
/// reversal) are taken as tangent.
inline constexpr double kCompCornerToleranceRad = 0.05;
/// rs274's TOLERANCE_EQUAL.
inline constexpr double kCompEqualTolerance = 1e-6;

/// Where an error is reported: the block being processed (rs274 reports a corner's failure on the block that
/// reveals it, not on the block whose end had to move).
struct CompErrorSite {
  const gcode::LineRef& where;
  int column;
  Error error(std::string_view message) const { return gcode::error_at(where, column, message); }
};

/// A compensated move waiting for the next one, which may still move its end within the plane.
struct QueuedMove {
  CanonicalMove move;  ///< as it will be emitted
  /// Lines: the direction rs274 remembers for the move (used to detect a reversed, gouging move when the end
  /// is pulled back). Entry lines remember the offset direction, later ones the programmed direction.
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();
  double original_sweep_rad = 0.0;  ///< arcs: sweep when queued (0: a corner arc, never checked)
  int turn = 0;                     ///< arcs: signed turn count in the plane frame (> 0 counter-clockwise)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< arcs: centre in the plane frame
};

struct CutterCompensation::Impl {
  // Mode
  bool on = false;
  bool first_move = true;  ///< the next compensated move is the entry move
  CompensationSide side = CompensationSide::left;
  double radius_mm = 0.0;
  Plane plane = Plane::xy;
  bool inch = false;             ///< program units, for rs274's unit-dependent tolerances
  bool arc_not_allowed = false;  ///< set by G40 after a compensated path: the next move must be straight
  // Positions (3-D, program coordinates)
  Eigen::Vector3d programmed_mm = Eigen::Vector3d::Zero();  ///< end of the last programmed move
  Eigen::Vector3d current_mm = Eigen::Vector3d::Zero();     ///< rs274's "current point" (tool centre)
  Eigen::Vector3d physical_mm = Eigen::Vector3d::Zero();    ///< end of the last move emitted or queued
  // Queue
  std::vector<QueuedMove> queue;
  Eigen::Vector2d endpoint = Eigen::Vector2d::Zero();  ///< start of the move last queued, when valid
  bool endpoint_valid = false;
  std::vector<CanonicalMove> released;  ///< emitted moves not yet handed out (G40 has no output vector)
  Eigen::Vector3d last_released_end_mm = Eigen::Vector3d::Zero();
  std::string last_source;  ///< for errors of flush(out), which has no location of its own
  int last_line = 0;

  // Plane frame helpers
  Eigen::Vector2d uv(const Eigen::Vector3d& p) const;
  double w(const Eigen::Vector3d& p) const;
  Eigen::Vector3d point(const Eigen::Vector2d& uv_mm, double w_mm) const;
  bool left() const { return side == CompensationSide::left; }
  /// rs274's TOOL_INSIDE_ARC: the tool is on the centre's side of an arc turning `turn`.
  bool tool_inside(int turn) const { return (left() && turn > 0) || (!left() && turn < 0); }
  int signed_turns(const CanonicalMove& arc) const;

  // Queue (ngc_cutter_compensation_queue.cpp)
  void set_endpoint(const Eigen::Vector2d& p);
  /// Emits every queued move (rs274's dequeue_canons).
  void release();
  /// Moves the plane end of every queued move to `p`, checks none reverses or overruns, and emits them.
  Status move_endpoint_and_release(const Eigen::Vector2d& p, const CompErrorSite& site);
  void enqueue_line(const CanonicalMove& from, MoveKind kind, const Eigen::Vector3d& end_mm,
                    const Eigen::Vector2d& direction);
  void enqueue_arc(const CanonicalMove& from, const Eigen::Vector2d& end_uv, double end_w,
                   const Eigen::Vector2d& centre_uv, int turn, double original_sweep_rad);
  void hand_out(std::vector<CanonicalMove>& out);

  // Moves (ngc_cutter_compensation_straight.cpp, ngc_cutter_compensation_arc.cpp)
  Status straight_entry(const CanonicalMove& m, const CompErrorSite& site);
  Status straight(const CanonicalMove& m, const CompErrorSite& site);
  Status straight_concave_corner(const Eigen::Vector2d& p, double theta_rad, double beta_rad,
                                 double gamma_rad, const CompErrorSite& site);
  Status arc_entry(const CanonicalMove& m, const CompErrorSite& site);
  Status arc(const CanonicalMove& m, const CompErrorSite& site);
  Status arc_concave_corner(const Eigen::Vector2d& centre, double arc_radius, int turn, double theta_rad,
                            double beta_rad, const CompErrorSite& site);
};

/// Angle swept from `from` to `to` about `centre` (rad, signed like `turn`; |turn| − 1 extra full turns), as
/// rs274's find_turn: an end at the start angle is a full turn.
double comp_sweep_rad(const Eigen::Vector2d& from, const Eigen::Vector2d& centre, int turn,
                      const Eigen::Vector2d& to);
inline Eigen::Vector2d comp_direction(double angle_rad) {
  return {std::cos(angle_rad), std::sin(angle_rad)};
}
inline double comp_angle(const Eigen::Vector2d& v) {
  return std::atan2(v.y(), v.x());
}

}  // namespace pkm::program::ngc
