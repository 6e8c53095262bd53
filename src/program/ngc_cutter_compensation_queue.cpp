// The queue of compensated moves whose end waits for the next move. A concave corner pulls the end of the
// queued moves back to where the two offset paths meet; the checks made then (a line that would run
// backwards, an arc that would sweep further than programmed) are rs274's gouge detection.
#include <numbers>

#include "program/ngc_cutter_compensation_impl.hpp"

namespace pkm::program::ngc {

double comp_sweep_rad(const Eigen::Vector2d& from, const Eigen::Vector2d& centre, int turn,
                      const Eigen::Vector2d& to) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  if (turn == 0) return 0.0;
  double start = comp_angle(from - centre);
  double end = comp_angle(to - centre);
  if (turn > 0) {
    if (end <= start) end += two_pi;
    return end - start + (turn - 1) * two_pi;
  }
  if (start <= end) start += two_pi;
  return end - start + (turn + 1) * two_pi;
}

void CutterCompensation::Impl::set_endpoint(const Eigen::Vector2d& p) {
  endpoint = p;
  endpoint_valid = true;
}

void CutterCompensation::Impl::release() {
  endpoint_valid = false;
  for (QueuedMove& q : queue) {
    // A queued dwell happens where the moves before it ended, which may have moved since it was queued.
    if (q.move.kind == MoveKind::dwell) {
      q.move.end_mm = last_released_end_mm;
    } else {
      last_released_end_mm = q.move.end_mm;
    }
    released.push_back(q.move);
  }
  queue.clear();
}

void CutterCompensation::Impl::hand_out(std::vector<CanonicalMove>& out) {
  for (CanonicalMove& m : released) {
    if (m.kind != MoveKind::dwell) last_released_end_mm = m.end_mm;
    out.push_back(std::move(m));
  }
  released.clear();
}

namespace {

// rs274 compares a sweep in radians with 0.001 in G20 and 0.0254 in G21: a length tolerance converted between
// units but applied to an angle. Kept as it is, since it decides which programs rs274 refuses.
double sweep_overrun_tolerance(bool inch) {
  return inch ? 0.001 : 0.0254;
}

}  // namespace

Status CutterCompensation::Impl::move_endpoint_and_release(const Eigen::Vector2d& p,
                                                           const CompErrorSite& site) {
  if (queue.empty()) return ok_status();
  for (QueuedMove& q : queue) {
    if (q.move.kind == MoveKind::dwell) continue;
    if (q.move.kind == MoveKind::arc) {
      const double r_before = (uv(q.move.end_mm) - q.centre).norm();
      const double r_after = (p - q.centre).norm();
      // Internal consistency (0.01 program units, as rs274): the new end must lie on the arc's circle.
      if (std::abs(r_before - r_after) > (inch ? 0.254 : 0.01))
        return site.error("BUG: cutter compensation has generated an invalid arc with mismatched radii");
      const double sweep = comp_sweep_rad(endpoint, q.centre, q.turn, p);
      if (q.original_sweep_rad != 0.0 && endpoint_valid &&
          std::abs(sweep) > std::abs(q.original_sweep_rad) + sweep_overrun_tolerance(inch))
        return site.error("Arc move in concave corner cannot be reached by the tool without gouging");
    } else if (endpoint_valid && q.direction.dot(p - endpoint) < 0.0) {
      // The pulled-back end lies behind the move's start: the offset path crosses itself.
      return site.error(
          q.move.kind == MoveKind::rapid
              ? "Straight traverse in concave corner cannot be reached by the tool without gouging"
              : "Straight feed in concave corner cannot be reached by the tool without gouging");
    }
    q.move.end_mm = point(p, w(q.move.end_mm));
  }
  physical_mm = point(p, w(physical_mm));
  release();
  set_endpoint(p);
  return ok_status();
}

void CutterCompensation::Impl::enqueue_line(const CanonicalMove& from, MoveKind kind,
                                            const Eigen::Vector3d& end_mm, const Eigen::Vector2d& direction) {
  QueuedMove q;
  q.move = from;
  q.move.kind = kind;
  q.move.end_mm = end_mm;
  q.direction = direction;
  queue.push_back(q);
  physical_mm = end_mm;
}

void CutterCompensation::Impl::enqueue_arc(const CanonicalMove& from, const Eigen::Vector2d& end_uv,
                                           double end_w, const Eigen::Vector2d& centre_uv, int turn,
                                           double original_sweep_rad) {
  QueuedMove q;
  q.move = from;
  q.move.kind = MoveKind::arc;
  q.move.end_mm = point(end_uv, end_w);
  // The arc starts where the tool is now; its centre is given at the start's height.
  q.move.center_mm = point(centre_uv, w(physical_mm));
  q.move.normal = turn > 0 ? gcode::plane_normal(plane) : Eigen::Vector3d(-gcode::plane_normal(plane));
  q.move.turns = std::abs(turn);
  q.move.plane = plane;
  q.turn = turn;
  q.centre = centre_uv;
  q.original_sweep_rad = original_sweep_rad;
  queue.push_back(q);
  physical_mm = q.move.end_mm;
}

}  // namespace pkm::program::ngc
