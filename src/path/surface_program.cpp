#include "path/surface_program.hpp"

namespace pkm::path {
namespace {

void add_surface_move(program::CanonicalProgram& out, program::MoveKind kind, const Eigen::Vector3d& end_mm,
                      const Eigen::Vector3d& axis, double feed_mm_min) {
  program::CanonicalMove move;
  move.line = static_cast<int>(out.moves.size()) + 1;
  move.kind = kind;
  move.end_mm = end_mm;
  move.orientation = program::OrientationSource::tool_axis;
  move.tool_axis = axis;
  if (kind == program::MoveKind::line) move.feed_mm_min = feed_mm_min;
  out.moves.push_back(move);
}

// A dwell of 0 s: the tool comes to rest on the surface. Without it the planner would round the corner
// between the approach along the tool axis and the first cut, and the cutting load on that blend, partly
// along the tool axis, would enter the surface error as a plunge the strategy does not make.
void add_surface_stop(program::CanonicalProgram& out, const SurfacePoint& at) {
  add_surface_move(out, program::MoveKind::dwell, at.position_mm, at.normal, 0.0);
}

void add_surface_retract(program::CanonicalProgram& out, const SurfacePoint& from, double clearance_mm) {
  add_surface_stop(out, from);
  add_surface_move(out, program::MoveKind::rapid, from.position_mm + clearance_mm * from.normal, from.normal,
                   0.0);
}

}  // namespace

program::CanonicalProgram surface_program(const SurfaceToolPath& path, const SurfaceProgramOptions& options) {
  using program::MoveKind;
  program::CanonicalProgram out;
  out.source = std::string(strategy_name(path.strategy));
  const SurfacePoint* last = nullptr;
  for (const SurfacePass& piece : path.pieces) {
    if (piece.points.empty()) continue;
    const SurfacePoint& first = piece.points.front();
    if (!piece.joined || last == nullptr) {  // lift off (after a previous piece) and come down on this one
      if (last != nullptr) add_surface_retract(out, *last, options.clearance_mm);
      add_surface_move(out, MoveKind::rapid, first.position_mm + options.clearance_mm * first.normal,
                       first.normal, 0.0);
      add_surface_move(out, MoveKind::rapid, first.position_mm, first.normal, 0.0);
      add_surface_stop(out, first);
    } else {
      add_surface_move(out, MoveKind::line, first.position_mm, first.normal, options.feed_mm_min);
    }
    for (std::size_t i = 1; i < piece.points.size(); ++i)
      add_surface_move(out, MoveKind::line, piece.points[i].position_mm, piece.points[i].normal,
                       options.feed_mm_min);
    last = &piece.points.back();
  }
  if (last != nullptr) add_surface_retract(out, *last, options.clearance_mm);
  out.end_line = static_cast<int>(out.moves.size());
  return out;
}

}  // namespace pkm::path
