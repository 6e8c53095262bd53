#pragma once
// From canonical moves to the geometric path in the machine's base frame.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/result.hpp"
#include "path/path.hpp"
#include "program/canonical_program.hpp"

namespace pkm::path {

/// How program coordinates sit in the machine.
struct PathFrame {
  Eigen::Vector3d program_origin_mm = Eigen::Vector3d::Zero();  ///< program X0 Y0 Z0 in the base frame
  /// The platform rotation at which the tool axis points along program +Z (the machine's home rotation).
  /// Tool-axis (CL) orientations are the shortest swing of this rotation that turns +Z onto the given axis.
  Eigen::Quaterniond reference_rotation = Eigen::Quaterniond::Identity();
  bool planar = false;  ///< a planar machine: A and B must be 0, C is the platform angle
};

struct PathOptions {
  double rapid_mm_s = 100.0;         ///< G0 speed of the tool point
  double max_feed_mm_s = 100.0;      ///< programmed feeds are capped here
  double angular_feed_deg_s = 60.0;  ///< speed of rotation-only rapids (and cap of rotation-only feeds)
  double path_tolerance_mm =
      0.01;  ///< corner blends stay within this distance of the programmed path; 0: stop
};

/// Builds the path, with corner blends where consecutive moves meet at an angle. Errors name the line.
Result<Path> build_path(const program::CanonicalProgram& program, const PathFrame& frame,
                        const PathOptions& options);

/// The platform rotation a move's orientation words ask for (A B C, or a tool axis with the free spin chosen
/// as the shortest swing from the reference rotation).
Eigen::Quaterniond program_rotation(const program::CanonicalMove& move, const PathFrame& frame);

}  // namespace pkm::path
