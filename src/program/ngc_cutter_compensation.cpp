// Cutter radius compensation: the mode (G40/G41/G42), the dispatch of programmed moves to the entry, straight
// and arc cases, and the hand-out of what the queue releases. The behaviour follows LinuxCNC 2.9's rs274,
// measured against it (tests/program/conformance/comp, scripts/regen-comp-golden.sh).
#include "program/ngc_cutter_compensation.hpp"

#include "program/ngc_cutter_compensation_impl.hpp"

namespace pkm::program::ngc {

Eigen::Vector2d CutterCompensation::Impl::uv(const Eigen::Vector3d& p) const {
  const gcode::PlaneAxes axes = gcode::axes_of(plane);
  return {p[axes.first], p[axes.second]};
}

double CutterCompensation::Impl::w(const Eigen::Vector3d& p) const {
  return p[gcode::axes_of(plane).normal];
}

Eigen::Vector3d CutterCompensation::Impl::point(const Eigen::Vector2d& uv_mm, double w_mm) const {
  const gcode::PlaneAxes axes = gcode::axes_of(plane);
  Eigen::Vector3d p;
  p[axes.first] = uv_mm.x();
  p[axes.second] = uv_mm.y();
  p[axes.normal] = w_mm;
  return p;
}

int CutterCompensation::Impl::signed_turns(const CanonicalMove& arc) const {
  const int turns = std::max(arc.turns, 1);
  return arc.normal.dot(gcode::plane_normal(plane)) >= 0.0 ? turns : -turns;
}

CutterCompensation::CutterCompensation() : impl_(std::make_unique<Impl>()) {}
CutterCompensation::~CutterCompensation() = default;
CutterCompensation::CutterCompensation(CutterCompensation&&) noexcept = default;
CutterCompensation& CutterCompensation::operator=(CutterCompensation&&) noexcept = default;

void CutterCompensation::set_position(const Eigen::Vector3d& position_mm) {
  impl_->programmed_mm = position_mm;
  impl_->current_mm = position_mm;
  impl_->physical_mm = position_mm;
}

void CutterCompensation::set_inch(bool inch) {
  impl_->inch = inch;
}

Status CutterCompensation::start(CompensationSide side, double radius_mm, Plane plane,
                                 const gcode::LineRef& where, int column) {
  Impl& s = *impl_;
  if (plane != Plane::xy && plane != Plane::zx)
    return gcode::error_at(where, column, "Cutter radius compensation allowed only in XY, XZ planes");
  if (s.on) return gcode::error_at(where, column, "Cannot turn cutter radius comp on when on");
  // A negative diameter in the tool table (a path programmed for a nominal tool larger than the real one)
  // means the other side with a positive radius, as in rs274.
  if (radius_mm < 0.0) {
    radius_mm = -radius_mm;
    side = side == CompensationSide::left ? CompensationSide::right : CompensationSide::left;
  }
  s.on = true;
  s.side = side;
  s.radius_mm = radius_mm;
  s.plane = plane;
  s.first_move = true;
  return ok_status();
}

Status CutterCompensation::select_plane(Plane plane, const gcode::LineRef& where, int column) {
  if (impl_->on && plane != impl_->plane)
    return gcode::error_at(where, column, "Cannot change planes with cutter radius compensation on");
  return ok_status();
}

Status CutterCompensation::stop(const gcode::LineRef& where, int column) {
  Impl& s = *impl_;
  if (s.on && s.radius_mm > 0.0 && !s.first_move) {
    // The last compensated move ends where it is: the exit move starts from the tool's offset position.
    const Status moved = s.move_endpoint_and_release(s.uv(s.current_mm), CompErrorSite{where, column});
    if (!moved) return moved;
    s.release();
    // rs274 takes the programmed point as its current point again; the next move goes straight there from
    // wherever the tool is, which is why it must not be an arc.
    s.current_mm = s.programmed_mm;
    s.arc_not_allowed = true;
  }
  s.on = false;
  s.first_move = true;
  return ok_status();
}

bool CutterCompensation::active() const {
  return impl_->on;
}

Status CutterCompensation::move(const CanonicalMove& programmed, const gcode::LineRef& where,
                                std::vector<CanonicalMove>& out) {
  return move(programmed, where, 1, out);
}

Status CutterCompensation::move(const CanonicalMove& programmed, const gcode::LineRef& where, int column,
                                std::vector<CanonicalMove>& out) {
  Impl& s = *impl_;
  s.last_source = where.source;
  s.last_line = where.line;
  const CompErrorSite site{where, column};
  Status status = ok_status();
  if (programmed.kind == MoveKind::dwell) {
    // A dwell waits behind the queued moves (it happens where the tool will be once they are final).
    if (s.queue.empty()) {
      CanonicalMove dwell = programmed;
      dwell.end_mm = s.physical_mm;
      s.released.push_back(dwell);
    } else {
      QueuedMove q;
      q.move = programmed;
      s.queue.push_back(q);
    }
  } else if (programmed.kind == MoveKind::arc && s.arc_not_allowed) {
    status = site.error("The move just after exiting cutter compensation mode must be straight, not an arc");
  } else if (!s.on || s.radius_mm <= 0.0) {
    s.arc_not_allowed = false;
    s.released.push_back(programmed);
    s.programmed_mm = programmed.end_mm;
    s.current_mm = programmed.end_mm;
    s.physical_mm = programmed.end_mm;
  } else if (programmed.kind == MoveKind::arc && programmed.plane != s.plane) {
    // The interpreter should have refused the plane change (select_plane); an arc in another plane has no
    // offset that rs274 would compute.
    status = site.error("Cannot change planes with cutter radius compensation on");
  } else if (programmed.kind == MoveKind::arc) {
    status = s.first_move ? s.arc_entry(programmed, site) : s.arc(programmed, site);
  } else {
    s.arc_not_allowed = false;
    status = s.first_move ? s.straight_entry(programmed, site) : s.straight(programmed, site);
  }
  s.hand_out(out);
  return status;
}

Status CutterCompensation::flush(std::vector<CanonicalMove>& out) {
  const gcode::LineRef where{impl_->last_source, impl_->last_line};
  return flush(out, where, 1);
}

Status CutterCompensation::flush(std::vector<CanonicalMove>& out, const gcode::LineRef& where, int column) {
  Impl& s = *impl_;
  // As rs274 at M0/M1/M2/M30: queued moves end where they are, after the same checks as at a corner.
  const Status moved = s.move_endpoint_and_release(s.uv(s.current_mm), CompErrorSite{where, column});
  s.release();
  s.hand_out(out);
  return moved;
}

Eigen::Vector3d CutterCompensation::tool_position_mm() const {
  return impl_->physical_mm;
}

}  // namespace pkm::program::ngc
