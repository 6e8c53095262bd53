#pragma once
// The nearest path point of a candidate position, for the estimating-function method (Smirnov 2019, §5.2.1).
// Smirnov 2019 measures a candidate against the straight line O_H → O_K: its perpendicular deviation δ (the
// determinant form of §5.2.1 is |(r − O_H) × (O_K − O_H)|/|O_K − O_H|) and its displacement along the line.
// For a whole program's path the same two numbers come from the nearest path point P(s*): the deviation is
// |p − P(s*)| and the progress is the increase of s* (mm of path). s* is found locally, by Newton steps on
// |P(s) − p|² from the current tact's path point: candidates lie a few drive steps away, so the search
// never jumps to another pass of the path that happens to come close (a full circle, a pocket's next lane).
// Only the coordinates the mechanism controls count (Mechanism::controlled_axes).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "machine/mechanism.hpp"
#include "path/path.hpp"

namespace pkm::interpolation {

struct EstimatingNearest {
  double s = 0.0;            ///< path parameter of the nearest point
  double distance_mm = 0.0;  ///< deviation: distance of the (masked) point from the path
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< the path's orientation there
};

class EstimatingProjector {
 public:
  EstimatingProjector(const path::Path& path, const AxisMask& axes);

  /// Sets the search start: the path point and tangent at s (once per tact, shared by all candidates).
  void anchor(double s);
  /// The nearest path point to `point_mm`, searched from the anchor within the distance the point can have
  /// moved along the path. No allocation.
  EstimatingNearest nearest(const Eigen::Vector3d& point_mm) const;
  /// Distance of `point_mm` from the path's end point (controlled coordinates).
  double distance_to_end_mm(const Eigen::Vector3d& point_mm) const;
  /// Source line of the segment containing s.
  int line_at(double s) const;
  double anchor_s() const { return anchor_s_; }

 private:
  struct Local {
    Eigen::Vector3d point;       ///< masked P(s)
    Eigen::Vector3d derivative;  ///< masked dP/ds
    Eigen::Quaterniond rotation;
  };
  Local local(double s, int& hint) const;
  Eigen::Vector3d mask(Eigen::Vector3d v) const {
    for (int c = 0; c < 3; ++c) {
      if (!controlled_[c]) v[c] = 0.0;
    }
    return v;
  }

  const path::Path& path_;
  std::array<bool, 3> controlled_{true, true, true};
  double length_ = 0.0;
  Eigen::Vector3d end_mm_ = Eigen::Vector3d::Zero();
  double anchor_s_ = 0.0;
  int anchor_hint_ = 0;
  Local anchor_;
};

}  // namespace pkm::interpolation
