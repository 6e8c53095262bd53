// Compensated arcs (G2/G3): the entry arc, and every later arc, concentric with the programmed one at one
// tool radius in or out, with the corner it makes with the move before it.
#include "program/ngc_cutter_compensation_impl.hpp"

namespace pkm::program::ngc {

// The entry arc cannot be concentric with the programmed one (the tool starts on the programmed path): rs274
// moves the end one radius in or out and runs an arc through the start and that end whose centre lies on the
// line from the new end to the programmed centre.
Status CutterCompensation::Impl::arc_entry(const CanonicalMove& m, const CompErrorSite& site) {
  const Eigen::Vector2d c = uv(current_mm);
  const Eigen::Vector2d e = uv(m.end_mm);
  const Eigen::Vector2d centre = uv(m.center_mm);
  const int turn = signed_turns(m);
  if ((e - c).norm() <= radius_mm)
    return site.error("Radius of cutter compensation entry arc is not greater than the tool radius");
  const bool inside = tool_inside(turn);
  if (inside && (centre - c).norm() <= radius_mm)
    return site.error("Tool radius not less than arc radius with comp");
  const double gamma = inside ? comp_angle(centre - e) : comp_angle(e - centre);
  const Eigen::Vector2d end = e + radius_mm * comp_direction(gamma);
  // Right triangle: end, new centre, midpoint of the chord from the start to the new end.
  const double half_chord = (c - end).norm() / 2.0;
  const double towards_centre = comp_angle(centre - end);
  const double corner = comp_angle(c - end) - towards_centre;
  if (std::abs(std::cos(corner)) < kCompEqualTolerance)
    return site.error("Tool radius not less than arc radius with comp");
  const Eigen::Vector2d new_centre = end + half_chord / std::cos(corner) * comp_direction(towards_centre);
  const double spiral_tolerance_mm = inch ? 0.002 * std::numbers::sqrt2 * 25.4 : 0.02 * std::numbers::sqrt2;
  if (std::abs((new_centre - end).norm() - (new_centre - c).norm()) > spiral_tolerance_mm)
    return site.error("Bug in tool radius comp");
  first_move = false;
  programmed_mm = m.end_mm;
  enqueue_arc(m, end, w(m.end_mm), new_centre, turn, comp_sweep_rad(c, new_centre, turn, end));
  current_mm = point(end, w(m.end_mm));
  return ok_status();
}

Status CutterCompensation::Impl::arc(const CanonicalMove& m, const CompErrorSite& site) {
  const Eigen::Vector2d o = uv(programmed_mm);
  const Eigen::Vector2d c = uv(current_mm);
  const Eigen::Vector2d e = uv(m.end_mm);
  const Eigen::Vector2d centre = uv(m.center_mm);
  const int turn = signed_turns(m);
  const double arc_radius = (centre - e).norm();
  // theta: direction of the last motion at its end; alpha: the arc's direction at its start; beta: the turn
  // between them, normalised into (-pi/2 .. 3pi/2].
  const double theta = comp_angle(c - o) + (left() ? -kPi / 2 : kPi / 2);
  double delta = comp_angle(centre - o);
  const double alpha = turn > 0 ? delta - kPi / 2 : delta + kPi / 2;
  double beta = left() ? theta - alpha : alpha - theta;
  if (beta > 1.5 * kPi) {
    beta -= 2 * kPi;
  } else if (beta < -kPi / 2) {
    beta += 2 * kPi;
  }
  const bool inside = tool_inside(turn);
  double gamma = 0.0;
  if (inside) {
    gamma = comp_angle(centre - e);
    if (arc_radius <= radius_mm) return site.error("Tool radius not less than arc radius with comp");
  } else {
    gamma = comp_angle(e - centre);
    delta += kPi;
  }
  const Eigen::Vector2d end = e + radius_mm * comp_direction(gamma);
  const double sweep = comp_sweep_rad(o, centre, turn, e);
  // Tangent arcs meeting at the top of an "m" (or a line meeting an arc atop an "h") are concave for rs274.
  const bool concave = beta < -kCompCornerToleranceRad || beta > kPi + kCompCornerToleranceRad ||
                       (std::abs(beta - kPi) < kCompCornerToleranceRad && !inside);
  if (concave) {
    const Status moved = arc_concave_corner(centre, arc_radius, turn, theta, beta, site);
    if (!moved) return moved;
  } else if (beta > kCompCornerToleranceRad) {
    // Convex: an arc about the programmed corner to the point one radius off the new arc's start.
    const Eigen::Vector2d mid = o + radius_mm * comp_direction(delta);
    release();
    enqueue_arc(m, mid, w(current_mm), o, left() ? -1 : 1, 0.0);
    release();
    set_endpoint(mid);
  } else {
    release();
    set_endpoint(c);
  }
  enqueue_arc(m, end, w(m.end_mm), centre, turn, sweep);
  programmed_mm = m.end_mm;
  current_mm = point(end, w(m.end_mm));
  return ok_status();
}

// A concave corner before an arc: the queued move ends where its offset path meets the new arc's.
Status CutterCompensation::Impl::arc_concave_corner(const Eigen::Vector2d& centre, double arc_radius,
                                                    int turn, double theta_rad, double beta_rad,
                                                    const CompErrorSite& site) {
  const bool inside = tool_inside(turn);
  if (queue.empty() || queue.front().move.kind != MoveKind::arc) {
    // Line to arc: the point of the offset circle one radius from the previous line.
    const double towards_line = arc_radius * std::sin(beta_rad - kPi / 2);
    const double from_centre = inside ? arc_radius - radius_mm : arc_radius + radius_mm;
    const double l = (inside ? towards_line + radius_mm : towards_line - radius_mm) / from_centre;
    if (l > 1.0 || l < -1.0)
      return site.error("Arc move in concave corner cannot be reached by the tool without gouging");
    double angle = 0.0;
    if (inside) {
      angle = turn > 0 ? theta_rad + std::asin(l) : theta_rad - std::asin(l);
    } else {
      angle = turn > 0 ? theta_rad + kPi - std::asin(l) : theta_rad + kPi + std::asin(l);
    }
    return move_endpoint_and_release(centre + from_centre * comp_direction(angle), site);
  }
  // Arc to arc: intersect the two offset circles (law of cosines about the previous arc's centre).
  const QueuedMove& prev = queue.front();
  const double old_radius = (prev.centre - uv(prev.move.end_mm)).norm();
  const double new_radius = inside ? arc_radius - radius_mm : arc_radius + radius_mm;
  const double centres_mm = (prev.centre - centre).norm();
  if (old_radius == 0.0 || centres_mm == 0.0)
    return site.error("Arc to arc motion is invalid because the arcs have the same center");
  const double a = (old_radius * old_radius + centres_mm * centres_mm - new_radius * new_radius) /
                   (2.0 * old_radius * centres_mm);
  if (a > 1.0 || a < -1.0)
    return site.error("Arc to arc motion makes a corner the compensated tool can't fit in without gouging");
  const double pullback = std::acos(a);
  const double centre_dir = comp_angle(centre - prev.centre);
  const bool plus = tool_inside(prev.turn) == (turn > 0);
  const double dir = plus ? centre_dir + pullback : centre_dir - pullback;
  return move_endpoint_and_release(prev.centre + old_radius * comp_direction(dir), site);
}

}  // namespace pkm::program::ngc
