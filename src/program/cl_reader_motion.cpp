// GOTO (one point or many), FROM, GOHOME, RAPID, CIRCLE and DELAY. Points are in the CL frame (the output
// stage transforms them); see docs/cl-data.md for each dialect's arc direction.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "program/cl_reader_state.hpp"

namespace pkm::program {
namespace {

constexpr double kUnitAxisTolerance = 1e-3;  // |(i,j,k)| of a written unit vector, to 4 decimals or so

bool looks_like_unit_vector(const double* v) {
  return std::abs(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0) < kUnitAxisTolerance;
}

}  // namespace

// GOTO/x,y,z[,i,j,k] and the multi-point forms of APT for point lists: x,y,z repeated, or x,y,z,i,j,k
// repeated under MULTAX/ON. Six values are one point and its tool axis (as every CAM system writes a 5-axis
// point) unless MULTAX/OFF was said; without MULTAX said, 6n values (n > 1) are n such points when every
// (i,j,k) is a unit vector, and triples otherwise.
Status ClReader::points(const ClStatement& s, std::vector<ClPoint>& out) const {
  out.clear();
  const std::size_t n = s.args.size();
  if (n < 3 || n % 3 != 0) {
    return error_at(
        s.at, fmt::format("{} takes x,y,z or x,y,z,i,j,k (or several of them), got {} values", s.word, n));
  }
  std::vector<double> v(n);
  if (auto status = numbers(s, 0, n, v.data()); !status) return status;
  bool sextuples = n % 6 == 0 && multax_.value_or(n == 6);
  if (!multax_.has_value() && n % 6 == 0 && n > 6) {
    sextuples = true;
    for (std::size_t k = 3; k < n && sextuples; k += 6) sextuples = looks_like_unit_vector(&v[k]);
  }
  if (multax_.value_or(false) && n % 6 != 0 && n != 3) {
    return error_at(s.at,
                    fmt::format("{} under MULTAX/ON takes x,y,z,i,j,k per point, got {} values", s.word, n));
  }
  const std::size_t stride = sextuples ? 6 : 3;
  for (std::size_t k = 0; k < n; k += stride) {
    ClPoint point{scale_ * Eigen::Vector3d(v[k], v[k + 1], v[k + 2]), std::nullopt};
    if (sextuples) {
      const Eigen::Vector3d axis(v[k + 3], v[k + 4], v[k + 5]);
      if (!(axis.norm() > 1e-9)) return error_at(s.args[k + 3].at, "the axis vector (i,j,k) has zero length");
      point.axis = axis.normalized();
    }
    out.push_back(point);
  }
  return ok_status();
}

Status ClReader::go_to(const ClStatement& s) {
  std::vector<ClPoint> list;
  if (auto status = points(s, list); !status) return status;
  if (list.size() > 1 && circle_) {
    return error_at(s.at, "a GOTO after CIRCLE takes one point: the arc's end");
  }
  for (const ClPoint& point : list) {
    if (point.axis) axis_ = *point.axis;
    if (cycle_active()) {
      if (auto status = cycle_point(s, point); !status) return status;
      continue;
    }
    if (auto status = go_to_point(s, point.p_mm); !status) return status;
  }
  return ok_status();
}

Status ClReader::go_to_point(const ClStatement& s, const Eigen::Vector3d& end_mm) {
  CanonicalMove move = move_to(s, rapid_next_ ? MoveKind::rapid : MoveKind::line, end_mm);
  if (circle_) {
    if (rapid_next_) return error_at(s.at, "RAPID cannot apply to a circular move (CIRCLE)");
    if (const std::string why = make_cl_arc(*circle_, position_, move); !why.empty())
      return error_at(s.at, why);
    circle_.reset();
    check_arc_direction(s, move);
  }
  if (move.kind != MoveKind::rapid) {
    if (auto status = set_feed(s, move); !status) return status;
  }
  rapid_next_ = false;
  position_ = end_mm;
  return emit(move, s.at);
}

// The direction the tool travels at the end of a cutting move; none after a rapid or a dwell (an arc after
// them has nothing to continue). Called by emit() for every move, the cycles' and splines' too.
void ClReader::remember_direction(const CanonicalMove& move, const Eigen::Vector3d& start_mm) {
  last_direction_.reset();
  if (move.kind == MoveKind::arc) {
    last_direction_ = cl_arc_end_tangent(move);
  } else if (move.kind == MoveKind::line && (move.end_mm - start_mm).norm() > 1e-9) {
    last_direction_ = (move.end_mm - start_mm).normalized();
  }
}

// Tangent continuity. SolidWorks CAM states the axis of the shorter of the two arcs between the points, also
// for an arc of more than 180° (which then runs the other way about it); of the two, the one that continues
// the move before it is meant. Every dialect: an arc that starts reversing the move before it is reported,
// the sign of a wrong arc convention (--format).
void ClReader::check_arc_direction(const ClStatement& s, CanonicalMove& arc) {
  if (!last_direction_) return;
  constexpr double kReversedCos = -0.9;  // more than about 154° from the previous direction
  constexpr double kTangentCos = 0.9;
  const double written = cl_arc_start_tangent(arc, position_).dot(*last_direction_);
  const bool full_turn = (arc.end_mm - position_).norm() < 1e-9;
  if (dialect_ == ProgramFormat::solidworks && !full_turn && written < kReversedCos &&
      cl_arc_sweep_rad(arc, position_) <= std::numbers::pi + 1e-9) {
    CanonicalMove longer = arc;
    longer.normal = -arc.normal;
    if (cl_arc_start_tangent(longer, position_).dot(*last_direction_) > kTangentCos) {
      arc = longer;
      ++longer_arcs_;
      return;
    }
  }
  if (written < kReversedCos) reversed_arc_lines_.push_back(s.at.line);
}

Status ClReader::from(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  std::vector<ClPoint> list;
  if (auto status = points(s, list); !status) return status;
  if (list.size() != 1) return error_at(s.at, "FROM takes one point (x,y,z or x,y,z,i,j,k)");
  if (list[0].axis) axis_ = *list[0].axis;
  const Eigen::Vector3d p = list[0].p_mm;
  if (output_.count() == 0 && !home_mm_) {
    home_mm_ = p;
    emitted_end_mm_ = p;
    program_.start_mm = apply_transforms_ ? Eigen::Vector3d(transform_ * p) : p;
    position_ = p;
    return ok_status();
  }
  // The tool is said to be elsewhere: get it there the way a post-processor would, by a rapid.
  rapid_next_ = false;
  position_ = p;
  return emit(move_to(s, MoveKind::rapid, p), s.at);
}

// GOHOME: a rapid back to the FROM point (the start when no FROM was given); NX writes the point itself
// (GOHOME/x,y,z), which is then where the tool goes.
Status ClReader::gohome(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (cycle_active()) return error_at(s.at, "GOHOME inside a CYCLE (CYCLE/OFF first)");
  Eigen::Vector3d home = home_mm_.value_or(initial_mm_);
  const bool words_only = std::all_of(s.args.begin(), s.args.end(),
                                      [](const ClArg& arg) { return cl_starts_like_word(arg.text); });
  if (!words_only) {  // GOHOME/x,y,z[,i,j,k]; the axis-naming variants (GOHOME/XAXIS…) all go home here
    std::vector<ClPoint> list;
    if (auto status = points(s, list); !status) return status;
    if (list.size() != 1) return error_at(s.at, "GOHOME takes one point (x,y,z or x,y,z,i,j,k)");
    if (list[0].axis) axis_ = *list[0].axis;
    home = list[0].p_mm;
  }
  rapid_next_ = false;
  position_ = home;
  return emit(move_to(s, MoveKind::rapid, home), s.at);
}

Status ClReader::rapid(const ClStatement& s) {
  if (auto status = no_values(s); !status) return status;
  rapid_next_ = true;
  return ok_status();
}

// CIRCLE/xc,yc,zc,i,j,k[,r[,…]][,CLOCKWISE|COUNTERCLOCKWISE|CLW|CCLW][,TIMES,n]. Numbers after the radius
// (NX appends tolerance and tool values) are checked as numbers and otherwise not used. The direction of
// travel about (i,j,k): the explicit word, else the dialect's convention (NX: clockwise; the others:
// counter-clockwise); the canonical arc is counter-clockwise about its normal, so a clockwise arc gets -axis.
Status ClReader::circle(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (s.args.size() < 6) {
    return error_at(
        s.at, fmt::format("CIRCLE takes at least 6 values (xc,yc,zc,i,j,k[,r]), got {}", s.args.size()));
  }
  std::array<double, 3> c{};
  if (auto status = numbers(s, 0, 3, c.data()); !status) return status;
  ClCircle circle;
  if (auto status = unit_vector(s, 3, circle.axis); !status) return status;
  std::optional<bool> clockwise;
  std::size_t numbers_after = 0;
  for (std::size_t i = 6; i < s.args.size(); ++i) {
    const ClArg& arg = s.args[i];
    if (!cl_starts_like_word(arg.text)) {
      double value = 0.0;
      if (auto status = number(arg, value); !status) return status;
      if (numbers_after++ == 0) {
        if (!(value > 0.0)) return error_at(arg.at, "the CIRCLE radius must be positive");
        circle.radius_mm = scale_ * value;
      }
    } else if (cl_equals_upper(arg.text, "CLOCKWISE") || cl_equals_upper(arg.text, "CLW")) {
      clockwise = true;
    } else if (cl_equals_upper(arg.text, "COUNTERCLOCKWISE") || cl_equals_upper(arg.text, "CCLW")) {
      clockwise = false;
    } else if (cl_equals_upper(arg.text, "TIMES")) {
      double turns = 0.0;
      if (i + 1 >= s.args.size()) return error_at(arg.at, "TIMES needs the number of turns");
      if (auto status = number(s.args[++i], turns); !status) return status;
      if (!(turns >= 1.0) || turns != std::floor(turns) || turns > 1e6)
        return error_at(s.args[i].at, "TIMES takes a whole number of turns, 1 or more");
      circle.turns = static_cast<int>(turns);
    } else {
      return error_at(arg.at, fmt::format("unknown CIRCLE modifier '{}'", arg.text));
    }
  }
  if (clockwise.value_or(dialect_ == ProgramFormat::nx)) circle.axis = -circle.axis;
  circle.center_mm = scale_ * Eigen::Vector3d(c[0], c[1], c[2]);
  circle_ = circle;
  circle_at_ = s.at;
  return ok_status();
}

// DELAY/s (seconds) or DELAY/REV,n (spindle revolutions): a dwell where the tool is.
Status ClReader::delay(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  double seconds = 0.0;
  if (s.args.size() == 1) {
    if (auto status = number(s.args[0], seconds); !status) return status;
  } else if (s.args.size() == 2 && cl_equals_upper(s.args[0].text, "REV")) {
    double revolutions = 0.0;
    if (auto status = number(s.args[1], revolutions); !status) return status;
    if (!spindle_rpm_known_) return error_at(s.args[0].at, "DELAY/REV needs a spindle speed (SPINDL/rpm)");
    seconds = revolutions / spindle_rpm_ * 60.0;
  } else {
    return error_at(s.at, "DELAY takes seconds (DELAY/s) or revolutions (DELAY/REV,n)");
  }
  if (!(seconds >= 0.0)) return error_at(s.args.back().at, "the dwell time must not be negative");
  CanonicalMove move = move_to(s, MoveKind::dwell, position_);
  move.dwell_s = seconds;
  return emit(move, s.at);
}

}  // namespace pkm::program
