#pragma once
// Contour error (Smirnov 2019, ρ): the perpendicular distance of the tool from the programmed path, not the
// lag along it. The published start-point value 4.9166e-4 mm is sqrt(Δy² + Δz²) on an X-directed line: the
// distance to the nearest path point, which is what this measures, for any path (lines, arcs, blends).
//
// The nearest point is found by Newton steps on the path parameter from a guess (the ideal point of the
// moment), so a point near the path costs a few path evaluations. Coordinates a reduced-DOF mechanism does
// not control follow from the others and are no error (Mechanism::controlled_axes).
#include <Eigen/Core>
#include <cmath>

#include "machine/machine.hpp"
#include "path/path.hpp"

namespace pkm::interpolation {

struct ContourDeviation {
  double distance_mm = 0.0;                  ///< perpendicular distance of the controlled point from the path
  double rotation_rad = 0.0;                 ///< angle between the pose's and the path's orientation there
  double s = 0.0;                            ///< path parameter of the nearest point
  Eigen::Vector3d offset_mm{0.0, 0.0, 0.0};  ///< point − nearest path point (controlled axes only)
};

class ContourGauge {
 public:
  ContourGauge(const Machine& machine, const path::Path& path);

  /// Nearest path point to `pose`'s controlled point, searching from `s_guess`; `hint` is a segment index.
  /// No allocation.
  ContourDeviation measure(const Pose& pose, double s_guess, int& hint) const noexcept;
  /// The tangent-line distance of a point at `offset_mm` (already masked) from a path point: its part
  /// perpendicular to the unit `tangent` there (the cheap form for many candidates near one path point,
  /// §5.2.5). The path ends `behind` before and `ahead` after the point (path units): a point beyond an end
  /// is that much farther from the path. Inline: the corrector calls it 128 times a period.
  static double line_distance(const Eigen::Vector3d& offset_mm, const Eigen::Vector3d& tangent, double behind,
                              double ahead) noexcept {
    const double along = offset_mm.dot(tangent);
    const double perpendicular2 = (offset_mm - along * tangent).squaredNorm();
    const double beyond = along > ahead ? along - ahead : along < -behind ? -behind - along : 0.0;
    return std::sqrt(perpendicular2 + beyond * beyond);
  }
  /// The unit tangent of the tool point's path at s (zero where only the orientation moves).
  Eigen::Vector3d tangent(double s, int& hint) const noexcept;
  /// Zeroes the coordinates the mechanism does not control.
  Eigen::Vector3d mask(Eigen::Vector3d offset_mm) const noexcept;
  bool controls_orientation() const { return controls_orientation_; }

 private:
  const path::Path& path_;
  std::array<bool, 3> controlled_{true, true, true};
  bool controls_orientation_ = true;
};

}  // namespace pkm::interpolation
