#include "path/path_builder.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "path/corner_blend.hpp"

namespace pkm::path {

using program::CanonicalMove;
using program::MoveKind;

Eigen::Quaterniond program_rotation(const CanonicalMove& move, const PathFrame& frame) {
  if (move.orientation == program::OrientationSource::tool_axis) {
    const Eigen::Quaterniond swing =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), move.tool_axis);
    return (swing * frame.reference_rotation).normalized();
  }
  const Eigen::Vector3d abc_rad = move.end_abc_deg * (std::numbers::pi / 180.0);
  return Eigen::Quaterniond(rotation_from_angles(AngleConvention::abc, abc_rad)).normalized();
}

namespace {

Error line_error(const program::CanonicalProgram& program, int line, const std::string& message) {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}: {}", program.source, line, message),
               ErrorLocation{program.source, line, 0, ""}};
}

double segment_speed_limit(const CanonicalMove& move, const Curve& curve, const PathOptions& options) {
  if (move.kind == MoveKind::rapid)
    return curve.rotation_only() ? options.angular_feed_deg_s : options.rapid_mm_s;
  const double cap = curve.rotation_only() ? options.angular_feed_deg_s : options.max_feed_mm_s;
  // G93: the move takes 1/F minutes, whatever its length.
  const double speed =
      move.inverse_time ? curve.param_length * move.inverse_time_per_min / 60.0 : move.feed_mm_min / 60.0;
  return std::min(speed, cap);
}

}  // namespace

Result<Path> build_path(const program::CanonicalProgram& program, const PathFrame& frame,
                        const PathOptions& options) {
  Path path;
  path.curves.reserve(program.moves.size());
  path.segments.reserve(program.moves.size());
  const Eigen::Vector3d tool_axis_platform = frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();

  CanonicalMove start_move;
  start_move.end_abc_deg = program.start_abc_deg;
  Eigen::Quaterniond rotation = program_rotation(start_move, frame);
  Eigen::Vector3d controlled = program.start_mm + frame.program_origin_mm;  // tool length 0 at the start
  path.start = {controlled, rotation};

  for (int m = 0; m < static_cast<int>(program.moves.size()); ++m) {
    const CanonicalMove& move = program.moves[m];
    if (move.kind == MoveKind::dwell) {
      if (path.segments.empty()) {
        path.initial_dwell_s += move.dwell_s;
      } else {
        path.segments.back().stop_after = true;
        path.segments.back().dwell_after_s += move.dwell_s;
      }
      continue;
    }
    if (frame.planar && (std::abs(move.end_abc_deg.x()) > 1e-9 || std::abs(move.end_abc_deg.y()) > 1e-9)) {
      return line_error(program, move.line,
                        "A and B must be 0 on a planar machine (C is the platform angle phi)");
    }
    const Eigen::Quaterniond end_rotation = program_rotation(move, frame);
    const double length = move.tool_length_mm;
    // Keep the controlled point continuous: after a tool-length change the tip starts where the new tool is.
    const Eigen::Vector3d tip_start = controlled - length * (rotation * tool_axis_platform);
    const Eigen::Vector3d tip_end = move.end_mm + frame.program_origin_mm;
    Curve curve;
    if (move.kind == MoveKind::arc) {
      const Eigen::Vector3d centre = move.center_mm + frame.program_origin_mm;
      const Eigen::Vector3d radial = tip_start - centre - move.normal * move.normal.dot(tip_start - centre);
      if (radial.norm() < 1e-9) return line_error(program, move.line, "arc radius is zero");
      curve = make_helix(tip_start, tip_end, centre, move.normal, std::max(1, move.turns), rotation,
                         end_rotation);
    } else {
      curve = make_line(tip_start, tip_end, rotation, end_rotation);
    }
    curve.tool_length_mm = length;
    curve.tool_axis_platform = tool_axis_platform;
    rotation = end_rotation;
    if (curve.param_length <= 1e-9) continue;  // nothing moves (LinuxCNC drops such moves too)
    controlled = curve.position(1.0);

    Segment seg;
    seg.curve_a = static_cast<int>(path.curves.size());
    seg.length = curve.param_length;
    seg.line = move.line;
    seg.move = m;
    seg.rapid = move.kind == MoveKind::rapid;
    seg.rotation_only = curve.rotation_only();
    seg.speed_limit = segment_speed_limit(move, curve, options);
    if (!(seg.speed_limit > 0.0)) {
      return line_error(program, move.line, "feed is 0: program F before the first feed move");
    }
    seg.tolerance_mm = move.path_tolerance_mm;
    // G61/G61.1 stop at the corner before the move; a change between moving the tool point and only rotating
    // is a corner no blend can join.
    if (!path.segments.empty() &&
        (move.exact_stop || path.segments.back().rotation_only != seg.rotation_only)) {
      path.segments.back().stop_after = true;
    }
    path.curves.push_back(curve);
    path.segments.push_back(seg);
  }
  if (!path.segments.empty()) path.segments.back().stop_after = true;

  blend_corners(path, options.path_tolerance_mm);
  double s = 0.0;
  for (Segment& seg : path.segments) {
    seg.s_start = s;
    s += seg.length;
  }
  return path;
}

}  // namespace pkm::path
