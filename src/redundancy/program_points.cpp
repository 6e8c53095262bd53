#include "redundancy/program_points.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "path/curve.hpp"
#include "path/path_builder.hpp"
#include "planning/motion_plan.hpp"

namespace pkm::redundancy {

using program::CanonicalMove;
using program::MoveKind;

namespace {

Error points_line_error(const program::CanonicalProgram& program, int line, const std::string& what) {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}: {}", program.source, line, what),
               ErrorLocation{program.source, line, 0, ""}};
}

path::Curve points_curve(const CanonicalMove& move, const Eigen::Vector3d& start_mm,
                         const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1,
                         const path::PathFrame& frame) {
  const Eigen::Vector3d end = move.end_mm + frame.program_origin_mm;
  if (move.kind == MoveKind::arc) {
    return path::make_helix(start_mm, end, move.center_mm + frame.program_origin_mm, move.normal,
                            std::max(1, move.turns), q0, q1);
  }
  return path::make_line(start_mm, end, q0, q1);
}

// R_axis: the shortest swing of the reference rotation that turns the tool axis onto `axis` (path_builder).
Eigen::Matrix3d axis_rotation_for(const Eigen::Vector3d& axis, const path::PathFrame& frame) {
  const Eigen::Quaterniond swing = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis);
  return (swing * frame.reference_rotation).normalized().toRotationMatrix();
}

// A B C (degrees) of a rotation, each of A and C turned by whole turns to lie nearest the previous value, so
// a controller's rotary axes never spin round between two parts of a move.
Eigen::Vector3d continuous_abc_deg(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& previous_deg,
                                   bool planar) {
  Eigen::Vector3d abc = deg_from_rad(1.0) * angles_from_rotation(AngleConvention::abc, rotation);
  if (planar) abc = {0.0, 0.0, deg_from_rad(std::atan2(rotation(1, 0), rotation(0, 0)))};
  for (int i : {0, 2}) abc[i] = previous_deg[i] + std::remainder(abc[i] - previous_deg[i], 360.0);
  return abc;
}

// Sets the orientation of `move` to `rotation`: the tool axis where asked and the move gave one, else A B C.
void set_orientation(CanonicalMove& move, const Eigen::Matrix3d& rotation, Eigen::Vector3d& abc, bool planar,
                     bool tool_axis, const Eigen::Vector3d& tool_axis_platform) {
  abc = continuous_abc_deg(rotation, abc, planar);
  if (tool_axis && move.orientation == program::OrientationSource::tool_axis) {
    move.tool_axis = (rotation * tool_axis_platform).normalized();
    return;
  }
  move.end_abc_deg = abc;
  move.orientation = program::OrientationSource::abc;
}

// The moves before the points (the approach) keep their orientation; written with A B C, a tool axis becomes
// the rotation the planner gives it (a dwell keeps the angles before it). Returns the angles at the end.
Eigen::Vector3d approach_as_abc(std::vector<CanonicalMove>& approach, const path::PathFrame& frame,
                                const Eigen::Vector3d& tool_axis_platform, Eigen::Vector3d abc) {
  for (CanonicalMove& move : approach) {
    if (move.orientation == program::OrientationSource::abc) {
      abc = move.end_abc_deg;
    } else if (move.kind == MoveKind::dwell) {
      move.end_abc_deg = abc;
      move.orientation = program::OrientationSource::abc;
    } else {
      set_orientation(move, path::program_rotation(move, frame).toRotationMatrix(), abc, frame.planar, false,
                      tool_axis_platform);
    }
  }
  return abc;
}

}  // namespace

program::CanonicalProgram program_through_poses(const program::CanonicalProgram& program,
                                                const ProgramPoints& points, const std::vector<Pose>& poses,
                                                bool keep_tool_axes, bool arcs_as_lines) {
  program::CanonicalProgram out = program;
  out.moves.assign(program.moves.begin(), program.moves.begin() + points.first_move);
  const bool planar = points.frame.planar;
  const Eigen::Vector3d origin = points.frame.program_origin_mm;
  const Eigen::Vector3d tool_axis_platform =
      points.frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();
  Eigen::Vector3d abc =
      points.first_move > 0 ? program.moves[points.first_move - 1].end_abc_deg : program.start_abc_deg;
  if (!keep_tool_axes)
    abc = approach_as_abc(out.moves, points.frame, tool_axis_platform, program.start_abc_deg);
  abc = continuous_abc_deg(poses[0].rotation, abc, planar);
  if (points.first_move > 0) {
    // The leading rapid ends where the points start.
    out.moves.back().end_mm = poses[0].position_mm - origin;
    set_orientation(out.moves.back(), poses[0].rotation, abc, planar, keep_tool_axes, tool_axis_platform);
  }
  Eigen::Vector3d start_mm = poses[0].position_mm - origin;
  std::size_t k = 1;
  for (int m = points.first_move; m < static_cast<int>(program.moves.size()); ++m) {
    const CanonicalMove& move = program.moves[m];
    if (move.kind == MoveKind::dwell) {
      CanonicalMove dwell = move;
      dwell.end_mm = start_mm;
      dwell.end_abc_deg = abc;
      dwell.orientation = program::OrientationSource::abc;
      out.moves.push_back(dwell);
      continue;
    }
    const int parts = points.parts[m];
    if (parts == 0) continue;  // a pure turn: the poses own the orientation
    const double axial_total = move.kind == MoveKind::arc ? move.normal.dot(move.end_mm - (start_mm)) : 0.0;
    for (int i = 1; i <= parts; ++i, ++k) {
      CanonicalMove part = move;
      part.end_mm = poses[k].position_mm - origin;
      set_orientation(part, poses[k].rotation, abc, planar, keep_tool_axes, tool_axis_platform);
      if (move.kind == MoveKind::arc) {
        if (arcs_as_lines) {
          part.kind = MoveKind::line;
        } else {
          // The centre is given at the start's height along the axis: each part starts higher on a helix.
          part.center_mm = move.center_mm + move.normal * (axial_total * (i - 1) / parts);
          part.turns = 1;
        }
      }
      if (move.inverse_time) part.inverse_time_per_min = move.inverse_time_per_min * parts;
      out.moves.push_back(part);
    }
    start_mm = out.moves.back().end_mm;
  }
  return out;
}

Result<ProgramCurves> program_curves(const program::CanonicalProgram& program, const Machine& machine) {
  ProgramCurves out;
  ProgramPoints& base = out.start;
  base.frame = planning::program_frame(machine);
  const path::PathFrame& frame = base.frame;
  const int move_count = static_cast<int>(program.moves.size());
  base.parts.assign(move_count, 0);
  out.curves.resize(move_count);
  out.program = &program;
  const Eigen::Vector3d tool_axis_platform = frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();

  int first_feed = -1;
  for (int m = 0; m < move_count; ++m) {
    const CanonicalMove& move = program.moves[m];
    if (move.tool_length_mm != 0.0) {
      return points_line_error(
          program, move.line,
          "tool-length offsets (G43) are not supported by the redundancy laws and pkm stiffness; "
          "program the tool point (G49) instead");
    }
    if (frame.planar && (std::abs(move.end_abc_deg.x()) > 1e-9 || std::abs(move.end_abc_deg.y()) > 1e-9)) {
      return points_line_error(program, move.line,
                               "A and B must be 0 on a planar machine (C is the platform angle phi)");
    }
    if (first_feed < 0 && (move.kind == MoveKind::line || move.kind == MoveKind::arc)) first_feed = m;
  }
  if (first_feed < 0) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: the program has no feed move (G1, G2, G3 or GOTO); there is nothing "
                                  "whose free coordinates could be chosen",
                                  program.source));
  }
  base.first_move = first_feed;

  // Where the tool is when the leading moves are done.
  program::CanonicalMove start_move;
  start_move.end_abc_deg = program.start_abc_deg;
  Eigen::Quaterniond rotation = path::program_rotation(start_move, frame);
  Eigen::Vector3d position = program.start_mm + frame.program_origin_mm;
  for (int m = 0; m < first_feed; ++m) {
    const CanonicalMove& move = program.moves[m];
    if (move.kind == MoveKind::dwell) continue;
    rotation = path::program_rotation(move, frame);
    position = move.end_mm + frame.program_origin_mm;
  }
  PathPoint start;
  start.position_mm = position;
  start.axis_rotation = axis_rotation_for(rotation * tool_axis_platform, frame);
  start.rotation = rotation.toRotationMatrix();
  start.line = program.moves[first_feed].line;
  base.points.push_back(start);
  base.start_rotation = rotation.toRotationMatrix();

  for (int m = first_feed; m < move_count; ++m) {
    const CanonicalMove& move = program.moves[m];
    if (move.kind == MoveKind::dwell) continue;
    const Eigen::Quaterniond end_rotation = path::program_rotation(move, frame);
    const path::Curve curve = points_curve(move, position, rotation, end_rotation, frame);
    rotation = end_rotation;
    position = curve.tip(1.0);
    if (curve.rotation_only()) continue;  // the laws choose the orientation; a pure turn has no place here
    out.curves[m] = curve;
  }
  return out;
}

int ProgramCurves::fewest_parts(int m) const {
  const CanonicalMove& move = program->moves[m];
  return move.kind == MoveKind::arc ? 2 * std::max(1, move.turns) : 1;  // sub-arcs < 1 turn
}

PathPoint ProgramCurves::point(int m, double f, const Eigen::Vector3d& previous_mm) const {
  const CanonicalMove& move = program->moves[m];
  const path::Curve& curve = *curves[m];
  const path::PathFrame& frame = start.frame;
  const Eigen::Vector3d tool_axis_platform = frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();
  PathPoint point;
  point.position_mm = curve.tip(f);
  const Eigen::Vector3d step = point.position_mm - previous_mm;
  point.step_mm = step.norm();
  if (point.step_mm > 0.0) point.tangent = step / point.step_mm;
  const Eigen::Quaterniond programmed = curve.rotation(f);
  point.axis_rotation = axis_rotation_for(programmed * tool_axis_platform, frame);
  point.rotation = programmed.toRotationMatrix();
  point.line = move.line;
  point.move_index = m;
  point.cutting = move.kind != MoveKind::rapid;
  point.feed_mm_s = point.cutting ? move.feed_mm_min / 60.0 : 0.0;
  return point;
}

void ProgramCurves::append_parts(int m, int parts, std::vector<PathPoint>& points) const {
  for (int i = 1; i <= parts; ++i)
    points.push_back(point(m, static_cast<double>(i) / parts, points.back().position_mm));
}

std::vector<statics::Wrench> point_loads(const ProgramPoints& points, const statics::LoadModel& loads,
                                         const Eigen::Vector3d& tool_axis_platform) {
  std::vector<statics::Wrench> wrenches(points.points.size());
  for (std::size_t k = 0; k < points.points.size(); ++k) {
    const PathPoint& point = points.points[k];
    statics::LoadPoint load_point;
    const PathPoint& travel = k == 0 && points.points.size() > 1 ? points.points[1] : point;
    load_point.tangent = travel.tangent;
    load_point.tool_axis = point.axis_rotation * tool_axis_platform;
    load_point.line = travel.line;
    load_point.cutting = travel.cutting;
    wrenches[k] = loads.wrench_at(load_point);
  }
  return wrenches;
}

ProgramPoints sample_curves(const ProgramCurves& curves, double step_mm) {
  ProgramPoints out = curves.start;
  for (int m = out.first_move; m < static_cast<int>(curves.curves.size()); ++m) {
    if (!curves.curves[m]) continue;
    const int parts = std::max(
        curves.fewest_parts(m),
        std::max(1, static_cast<int>(std::ceil(curves.curves[m]->translation_mm / step_mm * (1.0 - 1e-9)))));
    out.parts[m] = parts;
    curves.append_parts(m, parts, out.points);
  }
  return out;
}

Result<ProgramPoints> sample_program(const program::CanonicalProgram& program, const Machine& machine,
                                     double step_mm) {
  if (!(step_mm > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("path step: must be a positive length in mm, got {}", step_mm));
  }
  auto curves = program_curves(program, machine);
  if (!curves) return curves.error();
  return sample_curves(*curves, step_mm);
}

}  // namespace pkm::redundancy
