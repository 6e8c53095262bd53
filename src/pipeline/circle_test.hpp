#pragma once
// `pkm circle`: the circular test of ISO 230-4 on the machine in simulation (docs/servo.md, "The circle
// test"). A circle of the given radius and feed is programmed in a program plane (three turns
// counter-clockwise, then three clockwise), planned, and run through the drives' servo loops with every
// imperfection the machine file gives them; the tool's actual path is the forward kinematics of the
// actuators' simulated positions. Of each direction the middle turn is measured (its speed steady): the
// radial deviation from the least-squares circle along the angle, the circular deviation G (the radial band
// that holds the whole turn) and, between the two directions about their common centre, the circular
// hysteresis H. Written: circle.ngc, the plan with the servo files in plan/, circle.csv (the deviations),
// circle_summary.json and circle.svg (the polar plot).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "core/result.hpp"
#include "machine/machine.hpp"
#include "statics/load_model.hpp"

namespace pkm::pipeline {

struct CircleTestJob {
  double radius_mm = 30.0;
  double feed_mm_min = 3000.0;
  std::string plane = "XY";                             ///< XY (G17), ZX (G18) or YZ (G19)
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  ///< in program coordinates
  std::string out_directory;
  /// The machine in the loop (pipeline/simulate_program.hpp: the loops on the elastic machine, under `load`)
  /// instead of the loops on the rigid machine (pkm servo).
  bool elastic = false;
  statics::LoadModel load;
  ProgressSink progress;
};

/// One direction's measured turn.
struct CircleTrace {
  std::vector<double> angle_deg;     ///< of each tick about the common centre, 0 … 360
  std::vector<double> deviation_mm;  ///< its radius less the mean radius (common centre)
  double circular_deviation_mm =
      0.0;                 ///< G: max − min radius about this direction's own least-squares centre
  double radius_mm = 0.0;  ///< of its least-squares circle
};

struct CircleTestResult {
  CircleTrace counter_clockwise, clockwise;
  double hysteresis_mm = 0.0;  ///< H: the largest radial difference between the directions at one angle
  double max_contour_error_mm = 0.0;  ///< the servo run's, over the whole program
  nlohmann::json json;                ///< circle_summary.json
};

Result<CircleTestResult> circle_test(const Machine& machine, const CircleTestJob& job);

}  // namespace pkm::pipeline
