#pragma once
// The commanded tool path of a planned run, as the contour error is measured against it (docs/servo.md):
// the tool point of every servo tick, and between each two the cubic through the four around them at
// mid-period ((−p0 + 9p1 + 9p2 − p3)/16), so that the polyline's chords leave out 1/16 of a curve's sagitta
// v²T²/8R and a perfect servo's contour error is the plan's own path error; with the commanded speed at
// every tick. The coordinates the mechanism does not control are set to zero: they follow, and are no contour
// error (as the plan's own path error).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "servo/loop_design.hpp"
#include "servo/servo_plant.hpp"

namespace pkm::servo {

struct CommandedPath {
  std::vector<Eigen::Vector3d> points;  ///< tick k at 2k, the mid-period point at 2k + 1
  std::vector<double> time_s;
  std::vector<double> speed;  ///< per tick, by central differences, mm/s
  double fastest = 0.0;
};

CommandedPath commanded_path(const ServoRunInput& input, const AxisMask& axes);

/// `point` with the coordinates `axes` does not control set to zero.
Eigen::Vector3d controlled_point(const Eigen::Vector3d& point, const AxisMask& axes);

struct NearestOnPath {
  double distance_mm = 0.0;
  double time_s = 0.0;                              ///< the path's time there
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< the nearest point
};

/// The nearest point of the path's polyline between its points `first` … `last` to `point` (the latest of
/// equally near ones: where the path stands still, no lag).
NearestOnPath nearest_on_path(const CommandedPath& path, std::size_t first, std::size_t last,
                              const Eigen::Vector3d& point);

/// How far back (in ticks) the nearest path point can be: a few times the slowest position loop's time
/// constant.
std::size_t search_window(const LoopDesign& design, const ServoRunInput& input);

}  // namespace pkm::servo
