#pragma once
// The tool path built move by move, as a program is read: each canonical move becomes a curve, joined to
// the one before by a corner blend or a stop (corner_blend.hpp). A segment is final once the move after it
// is known (its end is trimmed by the blend into that move, or it stops there); final segments are appended
// to the path with their place s on it, so a streaming planner can sample them while the program is read.
#include <optional>
#include <string>

#include "core/result.hpp"
#include "path/path.hpp"
#include "path/path_builder.hpp"
#include "program/canonical_program.hpp"

namespace pkm::path {

class PathAppender {
 public:
  /// Appends to `path` (empty, or a window of this appender's own path), which starts at the program's start.
  PathAppender(std::string source, const program::CanonicalProgram& program, const PathFrame& frame,
               const PathOptions& options, Path& path);
  /// The next move, the `index`-th of the program. Errors name the line.
  Status add(const program::CanonicalMove& move, int index);
  /// The program ends: the last segment stops there and is appended.
  void finish();
  /// The length of the final path, the place s where the next final segment starts.
  double final_length() const { return s_; }
  /// Segments made so far (final or not), blends included.
  int blends() const { return blends_; }

 private:
  void append(const Segment& segment);

  std::string source_;
  PathFrame frame_;
  PathOptions options_;
  Path& path_;
  Eigen::Vector3d tool_axis_platform_;
  Eigen::Quaterniond rotation_;
  Eigen::Vector3d controlled_;
  std::optional<Segment> pending_;  ///< the last move's segment, waiting for the join with the next
  double s_ = 0.0;
  int blends_ = 0;
};

}  // namespace pkm::path
