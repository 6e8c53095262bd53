// The executor's motion: G0/G1 (and G53), G2/G3, G38.x probing, canned cycles, and the stops.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "program/gcode_arc.hpp"
#include "program/ngc_executor.hpp"
#include "program/ngc_executor_support.hpp"
#include "program/ngc_work_offsets.hpp"

namespace pkm::program::ngc {

using namespace executor_support;

namespace {

constexpr char kLinear[3] = {'X', 'Y', 'Z'};
constexpr char kRotary[3] = {'A', 'B', 'C'};
const char* motion_name(int motion) {
  switch (motion) {
    case 10:
      return "G1";
    case 20:
      return "G2";
    case 30:
      return "G3";
    default:
      return "G38";
  }
}

// Where to point at for an error about the block's move: its motion code, else its first axis or arc word.
int motion_column(const gcode::Block& b) {
  if (b.g[gcode::g_motion].given()) return b.g[gcode::g_motion].column;
  if (const int axis = b.first_axis_column(); axis > 0) return axis;
  for (const char letter : {'I', 'J', 'K', 'R'})
    if (b[letter].given()) return b[letter].column;
  return 1;
}

}  // namespace

Status Executor::target_of(const gcode::Block& b, Eigen::Vector3d& end, Eigen::Vector3d& abc_deg) const {
  const double scale = state_.mm_per_unit();
  end = state_.position_mm;
  abc_deg = state_.abc_deg;
  for (int i = 0; i < 3; ++i) {
    if (const gcode::Value& v = b[kLinear[i]]; v.given())
      end[i] = (state_.incremental ? state_.position_mm[i] : 0.0) + v.value * scale;
    if (const gcode::Value& v = b[kRotary[i]]; v.given())
      abc_deg[i] = (state_.incremental ? state_.abc_deg[i] : 0.0) + v.value;
  }
  if (b.polar_radius.given() || b.polar_angle.given()) return polar_target(b, end);
  return ok_status();
}

// LinuxCNC's polar words: `@` the distance from the program origin in the XY plane, `^` the angle (degrees
// from +X); in G91 they add to the current point's distance and angle. A word left out keeps the current one.
Status Executor::polar_target(const gcode::Block& b, Eigen::Vector3d& end) const {
  const int column = b.polar_radius.given() ? b.polar_radius.column : b.polar_angle.column;
  if (b['X'].given() || b['Y'].given())
    return gcode::error_at(where(), column, "Cannot specify X or Y words with polar coordinate");
  const double scale = state_.mm_per_unit();
  const Eigen::Vector2d current = state_.position_mm.head<2>();
  const bool at_origin = current.isZero(0.0);
  double radius_mm = current.norm();
  double angle_rad = std::atan2(current.y(), current.x());
  if (state_.incremental) {
    if (at_origin)
      return gcode::error_at(
          where(), column,
          b.polar_radius.given()
              ? "Incremental motion with polar coordinates is indeterminate when at the origin"
              : "G91 motion with polar coordinates is indeterminate when at the origin");
    if (b.polar_radius.given()) radius_mm += b.polar_radius.value * scale;
    if (b.polar_angle.given()) angle_rad += b.polar_angle.value * std::numbers::pi / 180.0;
  } else {
    if (b.polar_radius.given() && !b.polar_angle.given() && at_origin)
      return gcode::error_at(where(), column, "Must specify angle in polar coordinate if at the origin");
    if (b.polar_radius.given()) radius_mm = b.polar_radius.value * scale;
    if (b.polar_angle.given()) angle_rad = b.polar_angle.value * std::numbers::pi / 180.0;
  }
  end.x() = radius_mm * std::cos(angle_rad);
  end.y() = radius_mm * std::sin(angle_rad);
  return ok_status();
}

// G53: the named axes go to machine coordinates; the others stay.
Eigen::Vector3d Executor::machine_target_of(const gcode::Block& b, Eigen::Vector3d& abc_deg) const {
  Eigen::Vector3d machine = machine_mm(state_.position_mm);
  abc_deg = state_.abc_deg;
  for (int i = 0; i < 3; ++i) {
    if (const gcode::Value& v = b[kLinear[i]]; v.given()) machine[i] = v.value * state_.mm_per_unit();
    if (const gcode::Value& v = b[kRotary[i]]; v.given())
      abc_deg[i] = v.value - state_.frame.g5x_abc_deg[i] - state_.frame.g92_abc_deg[i];
  }
  Eigen::Vector3d end = program_from_machine_mm(machine);
  for (int i = 0; i < 3; ++i)
    if (!b[kLinear[i]].given()) end[i] = state_.position_mm[i];
  return end;
}

Status Executor::motion(const gcode::Block& b, int motion) {
  if (motion == 730 || (motion >= 810 && motion <= 890)) return cycle(b, motion);
  if (motion == 0 || motion == 10 || is_probe(motion)) return straight(b, motion);
  CanonicalMove m = new_move(MoveKind::arc);
  if (auto target = target_of(b, m.end_mm, m.end_abc_deg); !target) return target;
  if (auto fed = feed_for(b, motion, m); !fed) return fed;
  if (auto made = arc(b, motion, m); !made) return made;
  if (auto emitted = emit(m); !emitted) return emitted;
  state_.position_mm = m.end_mm;
  state_.abc_deg = m.end_abc_deg;
  return ok_status();
}

Status Executor::straight(const gcode::Block& b, int motion) {
  const bool machine = b.g[gcode::g_non_modal].is(530);
  if (machine && state_.incremental)
    return gcode::error_at(where(), b.g[gcode::g_non_modal].column, "Cannot use G53 incremental");
  if (machine && compensation_.active())
    return gcode::error_at(where(), b.g[gcode::g_non_modal].column, "Cannot use G53 with cutter radius comp");
  const Eigen::Vector3d start = state_.position_mm;
  CanonicalMove m = new_move(motion == 0 ? MoveKind::rapid : MoveKind::line);
  if (machine && (b.polar_radius.given() || b.polar_angle.given()))
    return gcode::error_at(where(), b.g[gcode::g_non_modal].column, "Cannot use polar coordinates with G53");
  if (machine) {
    m.end_mm = machine_target_of(b, m.end_abc_deg);
  } else if (auto target = target_of(b, m.end_mm, m.end_abc_deg); !target) {
    return target;
  }
  if (auto fed = feed_for(b, motion, m); !fed) return fed;
  if (m.inverse_time) {
    // rs274 reports an inverse-time feed as the equivalent XYZ speed; for rotary-only moves there is none.
    m.feed_mm_min = (m.end_mm - start).norm() * m.inverse_time_per_min;
  }
  if (is_probe(motion)) {
    if ((m.end_mm - start).norm() < 1e-9 && m.end_abc_deg == state_.abc_deg)
      return gcode::error_at(where(), motion_column(b), "Start point for straight probe equals end point");
    // Offline nothing can be touched: the probe ends at its target and reports no contact.
    add_event(fmt::format("{} probe (offline: no contact, the move ends at its target)",
                          gcode::code_name('G', motion)));
    for (int i = 0; i < 3; ++i) {
      parameters_.set(parameter::probe + i, m.end_mm[i] / state_.mm_per_unit());
      parameters_.set(parameter::probe + 3 + i, m.end_abc_deg[i]);
    }
    parameters_.set(parameter::probe_tripped, 0.0);
    m.probe = true;
  }
  if (auto emitted = emit(m); !emitted) return emitted;
  state_.position_mm = m.end_mm;
  state_.abc_deg = m.end_abc_deg;
  return ok_status();
}

Status Executor::feed_for(const gcode::Block& b, int motion, CanonicalMove& m) const {
  if (motion == 0) return ok_status();
  const char* name = motion_name(motion);
  if (state_.feed_mode == FeedMode::inverse_time) {
    const gcode::Value& f = b['F'];
    if (!f.given())
      return gcode::error_at(where(), motion_column(b),
                             fmt::format("{} in inverse-time mode (G93) needs an F word in its block", name));
    if (f.value <= 0.0) return gcode::error_at(where(), f.column, "inverse-time F must be greater than 0");
    m.inverse_time = true;
    m.inverse_time_per_min = f.value;
    return ok_status();
  }
  if (state_.feed <= 0.0) {
    const int column = b['F'].given() ? b['F'].column : motion_column(b);
    return gcode::error_at(where(), column, fmt::format("{} with no feed rate programmed (F)", name));
  }
  if (state_.feed_mode == FeedMode::units_per_revolution) {
    if (state_.spindle_speed <= 0.0 || state_.spindle_direction == 0)
      return gcode::error_at(
          where(), motion_column(b),
          fmt::format("{} in feed per revolution (G95) with the spindle not turning", name));
    m.feed_per_revolution_mm = state_.feed;
    m.feed_mm_min = state_.feed * state_.spindle_speed;
    return ok_status();
  }
  m.feed_mm_min = state_.feed;
  return ok_status();
}

Status Executor::arc(const gcode::Block& b, int motion, CanonicalMove& m) const {
  static constexpr char kOffsetLetter[3] = {'I', 'J', 'K'};  // centre offsets along X, Y, Z
  const char* const plane_name =
      state_.plane == Plane::xy ? "G17 (XY)" : (state_.plane == Plane::zx ? "G18 (XZ)" : "G19 (YZ)");
  const char* const name = motion_name(motion);
  const gcode::PlaneAxes axes = gcode::axes_of(state_.plane);
  const double scale = state_.mm_per_unit();
  const Eigen::Vector3d start = state_.position_mm;
  if (const gcode::Value& v = b[kOffsetLetter[axes.normal]]; v.given())
    return gcode::error_at(where(), v.column,
                           fmt::format("{} word in a {} arc", kOffsetLetter[axes.normal], plane_name));
  const gcode::Value& first = b[kOffsetLetter[axes.first]];
  const gcode::Value& second = b[kOffsetLetter[axes.second]];
  const gcode::Value& r = b['R'];
  if (r.given() && (first.given() || second.given()))
    return gcode::error_at(where(), r.column, "R and I/J/K in one arc: give the centre one way");
  if (!r.given() && !first.given() && !second.given())
    return gcode::error_at(where(), motion_column(b), fmt::format("{} with no I, J, K or R", name));
  if (const gcode::Value& p = b['P']; p.given()) {
    if (!is_whole(p.value) || p.value < 1.0 || p.value > kLargestCount)
      return gcode::error_at(where(), p.column,
                             fmt::format("{} P (turns) must be a whole number from 1 to 1000000", name));
    m.turns = static_cast<int>(std::lround(p.value));
  }
  const bool clockwise = motion == 20;
  const gcode::ArcTolerances tolerances = gcode::arc_tolerances(state_.inch);
  Eigen::Vector3d centre = start;
  if (r.given()) {
    const gcode::ArcProblem problem = gcode::centre_from_radius(start, m.end_mm, r.value * scale, clockwise,
                                                                state_.plane, tolerances, centre);
    if (!problem.message.empty()) return gcode::error_at(where(), r.column, problem.message);
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
            where(), column,
            fmt::format("{} word missing: absolute arc centres (G90.1) need both", kOffsetLetter[axis]));
      }
    }
    const gcode::ArcProblem problem =
        gcode::check_centre_arc(start, m.end_mm, centre, state_.plane, tolerances);
    const int column = first.given() ? first.column : second.column;
    if (!problem.message.empty()) return gcode::error_at(where(), column, problem.message);
  }
  m.kind = MoveKind::arc;
  m.center_mm = centre;
  m.normal = gcode::plane_normal(state_.plane) * (clockwise ? -1.0 : 1.0);
  if (m.inverse_time) m.feed_mm_min = gcode::arc_length_mm(start, m) * m.inverse_time_per_min;
  return ok_status();
}

Status Executor::cycle(const gcode::Block& b, int motion) {
  if (compensation_.active())
    return gcode::error_at(where(), motion_column(b), "Cannot use canned cycles with cutter compensation on");
  CycleContext context;
  context.code = motion;
  context.plane = state_.plane;
  context.retract_to_r = state_.retract_to_r;
  context.incremental = state_.incremental;
  context.inch = state_.inch;
  context.position_mm = state_.position_mm;
  context.spindle_speed = state_.spindle_speed;
  context.spindle_clockwise = state_.spindle_direction >= 0;
  context.spindle_turning = state_.spindle_direction != 0;
  if (state_.feed <= 0.0 && state_.feed_mode != FeedMode::inverse_time)
    return gcode::error_at(where(), motion_column(b),
                           fmt::format("{} with no feed rate programmed (F)", gcode::code_name('G', motion)));
  // LinuxCNC runs a cycle in exact-path mode, whatever the program's path control.
  const bool exact = state_.exact_stop;
  state_.exact_stop = true;
  cycle_status_ = ok_status();
  // The moves of all the cycles count against max_blocks: an L or a Q can make a block of millions of them.
  context.max_moves = options_.max_blocks > cycle_moves_ ? options_.max_blocks - cycle_moves_ : 0;
  const std::size_t moves_before = output_.count();
  Status ran = run_canned_cycle(b, where(), context, cycle_memory_, *this);
  cycle_moves_ += output_.count() - moves_before;
  if (ran && cycle_status_ && (cycle_memory_.end_mm - state_.position_mm).norm() > 1e-9) {
    // After G88 (the operator retracts by hand) and G84 outside G17, LinuxCNC takes the tool to be at the
    // clear plane although no move took it there; pkm's path must be continuous, so a rapid does.
    CanonicalMove m = new_move(MoveKind::rapid);
    m.end_mm = cycle_memory_.end_mm;
    m.inserted = true;
    cycle_status_ = emit(m);
    state_.position_mm = cycle_memory_.end_mm;
  }
  state_.exact_stop = exact;
  if (!ran) return ran;
  return cycle_status_;
}

// CycleSink: each step of a cycle is a move from where the tool is.
void Executor::rapid(const Eigen::Vector3d& to_mm) {
  CanonicalMove m = new_move(MoveKind::rapid);
  m.end_mm = to_mm;
  if (cycle_status_) cycle_status_ = emit(m);
  state_.position_mm = to_mm;
}

void Executor::feed(const Eigen::Vector3d& to_mm) {
  CanonicalMove m = new_move(MoveKind::line);
  m.end_mm = to_mm;
  m.feed_mm_min =
      state_.feed_mode == FeedMode::units_per_revolution ? state_.feed * state_.spindle_speed : state_.feed;
  if (cycle_status_) cycle_status_ = emit(m);
  state_.position_mm = to_mm;
}

void Executor::dwell(double seconds) {
  CanonicalMove m = new_move(MoveKind::dwell);
  m.dwell_s = seconds;
  if (cycle_status_) cycle_status_ = emit(m);
}

void Executor::event(const std::string& what) {
  add_event(what);
}

// M0/M1/M60 pause the program: the move before comes to a stop there. M2/M30 end it.
Status Executor::stop(const gcode::Block& b) {
  const gcode::Code& code = b.m[gcode::m_stop];
  if (!code.given()) return ok_status();
  if (code.is(20) || code.is(300)) {
    ended_ = true;
    return ok_status();
  }
  // rs274 empties compensation's queue at a pause (compensation stays on).
  if (auto flushed = flush_compensation(); !flushed) return flushed;
  add_event(gcode::code_name('M', code.number));
  if (CanonicalMove* last = output_.last()) last->exact_stop = true;
  return ok_status();
}

}  // namespace pkm::program::ngc
