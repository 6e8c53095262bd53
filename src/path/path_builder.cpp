#include "path/path_builder.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "path/path_appender.hpp"

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

Result<Path> build_path(const program::CanonicalProgram& program, const PathFrame& frame,
                        const PathOptions& options) {
  Path path;
  path.curves.reserve(program.moves.size());
  path.segments.reserve(program.moves.size());
  PathAppender appender(program.source, program, frame, options, path);
  for (int m = 0; m < static_cast<int>(program.moves.size()); ++m) {
    if (Status added = appender.add(program.moves[m], m); !added) return added.error();
  }
  appender.finish();
  return path;
}

}  // namespace pkm::path
