#pragma once
// What a calibration is identified from (Smirnov 2019, §5.2.4): the drives' readings at a number of poses,
// and at each pose what was measured of the platform — positions of targets fixed to it (a laser tracker, a
// CMM touching the vertices of the dissertation's triangular plate), or the length of a ballbar between the
// tool point and a ball fixed to the table. Read from CSV by io/measurement_file.hpp; made by simulation in
// calibration/simulate.hpp. Plain data in io/ (the layer of its readers, below the calibration in
// pkm::motion); the namespace stays pkm::calibration.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "machine/mechanism.hpp"

namespace pkm::calibration {

/// A target on the platform: its position in the tool frame (origin at the tool point, platform axes), mm.
struct FixtureTarget {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
};

/// One measured target position at one pose, base frame, mm.
struct TargetObservation {
  int target = 0;  ///< index into MeasurementSet::fixture
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  double sigma_mm = 0.0;  ///< standard deviation of each coordinate (> 0)
  int line = 0;           ///< line of the source file, for messages (0: simulated)
};

/// One ballbar reading: distance from the tool point to the ball centre MeasurementSet::ballbar_centre_mm.
struct DistanceObservation {
  double distance_mm = 0.0;
  double sigma_mm = 0.0;
  int line = 0;
};

/// One pose of the machine: the drive readings (mm, or rad for angular actuators) and what was measured
/// there.
struct MeasuredPose {
  std::string id;
  ActuatorVector readings;
  std::vector<TargetObservation> targets;      ///< tracker / CMM
  std::vector<DistanceObservation> distances;  ///< ballbar
  int line = 0;                                ///< first line of the pose in the source file (0: simulated)
};

enum class MeasurementKind { targets, ballbar };

struct MeasurementSet {
  std::string source;  ///< file name (or "simulated")
  MeasurementKind kind = MeasurementKind::targets;
  std::vector<FixtureTarget> fixture;                           ///< targets (kind targets)
  Eigen::Vector3d ballbar_centre_mm = Eigen::Vector3d::Zero();  ///< ball on the table (kind ballbar)
  std::vector<MeasuredPose> poses;
};

}  // namespace pkm::calibration
