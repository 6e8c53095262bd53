// Compensated straight moves (G0/G1): the entry move, and every later line with the corner it makes with
// the move before it — convex (an arc about the programmed corner is inserted), concave (the queued move is
// cut short where the offset paths meet) or tangent.
#include "program/ngc_cutter_compensation_impl.hpp"

namespace pkm::program::ngc {

Status CutterCompensation::Impl::straight_entry(const CanonicalMove& m, const CompErrorSite& site) {
  const Eigen::Vector2d c = uv(current_mm);
  const Eigen::Vector2d p = uv(m.end_mm);
  if ((p - c).norm() <= radius_mm)
    return site.error("Length of cutter compensation entry move is not greater than the tool radius");
  // The tool goes straight to the point one radius beside the programmed end, square to the entry move.
  const double offset_angle = comp_angle(p - c) + (left() ? kPi / 2 : -kPi / 2);
  const Eigen::Vector2d end = p + radius_mm * comp_direction(offset_angle);
  set_endpoint(c);
  // rs274 remembers the offset direction (not the motion's) for the entry move's reversal check.
  enqueue_line(m, m.kind, point(end, w(m.end_mm)), comp_direction(offset_angle));
  first_move = false;
  current_mm = point(end, w(m.end_mm));
  programmed_mm = m.end_mm;
  return ok_status();
}

Status CutterCompensation::Impl::straight(const CanonicalMove& m, const CompErrorSite& site) {
  const Eigen::Vector2d c = uv(current_mm);
  const Eigen::Vector2d o = uv(programmed_mm);
  const Eigen::Vector2d p = uv(m.end_mm);
  const double pw = w(m.end_mm);
  if (p.x() == o.x() && p.y() == o.y()) {
    // No motion in the plane (a plunge): the tool stays beside the programmed point; the queue keeps it.
    enqueue_line(m, m.kind, point(c, pw), Eigen::Vector2d::Zero());
    current_mm = point(c, pw);
    programmed_mm = m.end_mm;
    return ok_status();
  }
  // theta: from the programmed point to the tool (square to the last motion); alpha: the new direction.
  // beta measures the turn between them, in (-pi/2 .. 3pi/2) around the tangent case 0.
  double theta = comp_angle(c - o);
  double alpha = comp_angle(p - o);
  double beta = 0.0;
  double gamma = 0.0;
  if (left()) {
    if (theta < alpha) theta += 2 * kPi;
    beta = theta - alpha - kPi / 2;
    gamma = kPi / 2;
  } else {
    if (alpha < theta) alpha += 2 * kPi;
    beta = alpha - theta - kPi / 2;
    gamma = -kPi / 2;
  }
  const Eigen::Vector2d end = p + radius_mm * comp_direction(alpha + gamma);
  const Eigen::Vector2d mid = o + radius_mm * comp_direction(alpha + gamma);
  const bool front_is_arc = !queue.empty() && queue.front().move.kind == MoveKind::arc;
  // Leaving the top of an arc the tool is outside of, straight back along it ("h" shape): rs274 takes the
  // corner as concave (stays on the same side) rather than looping around.
  const bool concave =
      beta < -kCompCornerToleranceRad || beta > kPi + kCompCornerToleranceRad ||
      (beta > kPi - kCompCornerToleranceRad && front_is_arc && !tool_inside(queue.front().turn));
  if (!concave && beta > kCompCornerToleranceRad) {
    // Convex: the queued move keeps its end; an arc about the programmed corner (a straight traverse for G0,
    // which has no arc) brings the tool square to the new direction. It carries all of A, B, C's motion.
    const Status moved = move_endpoint_and_release(c, site);
    if (!moved) return moved;
    if (m.kind == MoveKind::rapid) {
      enqueue_line(m, MoveKind::rapid, point(mid, w(current_mm)), Eigen::Vector2d::Zero());
    } else {
      enqueue_arc(m, mid, w(current_mm), o, left() ? -1 : 1, 0.0);
    }
    release();
    set_endpoint(mid);
  } else if (concave) {
    const Status moved = straight_concave_corner(p, theta, beta, gamma, site);
    if (!moved) return moved;
  } else {
    release();
    set_endpoint(c);
  }
  enqueue_line(m, m.kind, point(end, pw), p - o);
  current_mm = point(end, pw);
  programmed_mm = m.end_mm;
  return ok_status();
}

// A concave corner before a line: the queued move ends where its offset path meets the new line's.
Status CutterCompensation::Impl::straight_concave_corner(const Eigen::Vector2d& p, double theta_rad,
                                                         double beta_rad, double gamma_rad,
                                                         const CompErrorSite& site) {
  const Eigen::Vector2d c = uv(current_mm);
  const Eigen::Vector2d o = uv(programmed_mm);
  if (queue.empty() || queue.front().move.kind != MoveKind::arc) {
    // Line to line: back up along the previous line by r / tan(half the inside angle).
    const double half_corner = (beta_rad + kPi) / 2.0;
    if (half_corner == 0.0) return site.error("Zero degree inside corner is invalid for cutter compensation");
    const double retreat = radius_mm / std::tan(half_corner);
    return move_endpoint_and_release(c + retreat * comp_direction(theta_rad + gamma_rad), site);
  }
  // Arc to line: the point of the (compensated) arc one radius from the new line.
  const QueuedMove& prev = queue.front();
  const double old_radius = (prev.centre - uv(prev.move.end_mm)).norm();
  const double base_dir = comp_angle(p - o);
  const double normal_dir = prev.turn > 0 ? base_dir + kPi / 2 : base_dir - kPi / 2;
  const double phi = comp_angle(prev.centre - o);
  const bool inside = tool_inside(prev.turn);
  const double programmed_radius = inside ? old_radius + radius_mm : old_radius - radius_mm;
  // Distance from the arc's centre to the new line, then to the new line's offset path.
  const double d = programmed_radius * std::cos(normal_dir - phi);
  const double l = (inside ? d - radius_mm : d + radius_mm) / old_radius;
  if (l > 1.0 || l < -1.0)
    return site.error(
        "Arc to straight motion makes a corner the compensated tool can't fit in without gouging");
  const bool plus = inside == (prev.turn <= 0);
  const double angle = (plus ? std::acos(l) : -std::acos(l)) + normal_dir + kPi;
  return move_endpoint_and_release(prev.centre + old_radius * comp_direction(angle), site);
}

}  // namespace pkm::program::ngc
