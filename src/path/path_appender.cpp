#include "path/path_appender.hpp"

#include <fmt/format.h>

#include <cmath>

#include "path/corner_blend.hpp"

namespace pkm::path {

using program::CanonicalMove;
using program::MoveKind;

namespace {

Error line_error(const std::string& source, int line, const std::string& message) {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}: {}", source, line, message),
               ErrorLocation{source, line, 0, ""}};
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

/// The platform rotation at the program's start: its A B C.
Eigen::Quaterniond start_rotation(const program::CanonicalProgram& program, const PathFrame& frame) {
  CanonicalMove start_move;
  start_move.end_abc_deg = program.start_abc_deg;
  return program_rotation(start_move, frame);
}

}  // namespace

PathAppender::PathAppender(std::string source, const program::CanonicalProgram& program,
                           const PathFrame& frame, const PathOptions& options, Path& path)
    : source_(std::move(source)),
      frame_(frame),
      options_(options),
      path_(path),
      tool_axis_platform_(frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ()),
      rotation_(start_rotation(program, frame)),
      controlled_(program.start_mm + frame.program_origin_mm) {  // tool length 0 at the start
  path_.start = {controlled_, rotation_};
}

void PathAppender::append(const Segment& segment) {
  if (is_sliver(segment)) return;  // trimming left (almost) nothing of it between two blends
  path_.segments.push_back(segment);
  path_.segments.back().s_start = s_;
  s_ += segment.length;
}

Status PathAppender::add(const CanonicalMove& move, int index) {
  if (move.kind == MoveKind::dwell) {
    if (!pending_) {
      path_.initial_dwell_s += move.dwell_s;
    } else {
      pending_->stop_after = true;
      pending_->dwell_after_s += move.dwell_s;
    }
    return ok_status();
  }
  if (frame_.planar && (std::abs(move.end_abc_deg.x()) > 1e-9 || std::abs(move.end_abc_deg.y()) > 1e-9))
    return line_error(source_, move.line,
                      "A and B must be 0 on a planar machine (C is the platform angle phi)");
  const Eigen::Quaterniond end_rotation = program_rotation(move, frame_);
  const double length = move.tool_length_mm;
  // Keep the controlled point continuous: after a tool-length change the tip starts where the new tool is.
  const Eigen::Vector3d tip_start = controlled_ - length * (rotation_ * tool_axis_platform_);
  const Eigen::Vector3d tip_end = move.end_mm + frame_.program_origin_mm;
  Curve curve;
  if (move.kind == MoveKind::arc) {
    const Eigen::Vector3d centre = move.center_mm + frame_.program_origin_mm;
    const Eigen::Vector3d radial = tip_start - centre - move.normal * move.normal.dot(tip_start - centre);
    if (radial.norm() < 1e-9) return line_error(source_, move.line, "arc radius is zero");
    curve =
        make_helix(tip_start, tip_end, centre, move.normal, std::max(1, move.turns), rotation_, end_rotation);
  } else {
    curve = make_line(tip_start, tip_end, rotation_, end_rotation);
  }
  curve.tool_length_mm = length;
  curve.tool_axis_platform = tool_axis_platform_;
  rotation_ = end_rotation;
  if (curve.param_length <= 1e-9) return ok_status();  // nothing moves (LinuxCNC drops such moves too)
  controlled_ = curve.position(1.0);

  Segment seg;
  seg.curve_a = path_.curve_base + static_cast<int>(path_.curves.size());
  seg.length = curve.param_length;
  seg.line = move.line;
  seg.move = index;
  seg.rapid = move.kind == MoveKind::rapid;
  seg.rotation_only = curve.rotation_only();
  seg.speed_limit = segment_speed_limit(move, curve, options_);
  if (!(seg.speed_limit > 0.0))
    return line_error(source_, move.line, "feed is 0: program F before the first feed move");
  seg.tolerance_mm = move.path_tolerance_mm;
  path_.curves.push_back(curve);
  if (!pending_) {
    pending_ = seg;
    return ok_status();
  }
  // G61/G61.1 stop at the corner before the move; a change between moving the tool point and only rotating
  // is a corner no blend can join.
  if (move.exact_stop || pending_->rotation_only != seg.rotation_only) pending_->stop_after = true;
  const std::optional<Segment> blend = join_corner(path_, *pending_, seg, options_.path_tolerance_mm);
  append(*pending_);
  if (blend) {
    append(*blend);
    ++blends_;
  }
  pending_ = seg;
  return ok_status();
}

void PathAppender::finish() {
  if (!pending_) return;
  pending_->stop_after = true;
  append(*pending_);
  pending_.reset();
}

}  // namespace pkm::path
