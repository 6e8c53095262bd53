#pragma once
// `pkm modes --pose` (and Python's pkm.modes) as one library call: the natural frequencies and mode shapes of
// the machine's elastic struts at a pose (dynamics/natural_frequencies.hpp), the drives clamped there, about
// the static equilibrium under gravity, with how far that equilibrium sags from the pose.
#include <string>
#include <vector>

#include "dynamics/natural_frequencies.hpp"
#include "machine/machine.hpp"

namespace pkm::pipeline {

struct ModesJob {
  Pose pose;
  /// How messages about the pose name it (the CLI: "--pose 0,0,5000,0,0,0"); empty: not named.
  std::string pose_name;
};

struct ModesJobResult {
  dynamics::NaturalModes modes;
  /// Per basis coordinate the twist component it moves: x_mm, y_mm, z_mm (tool point), rx_rad … rz_rad.
  std::vector<std::string> coordinates;
  Eigen::Vector3d static_deflection_mm =
      Eigen::Vector3d::Zero();       ///< the equilibrium's tool point − the pose's
  double static_rotation_deg = 0.0;  ///< the equilibrium's rotation from the pose
};

/// Refuses a pose the drives cannot hold (out of reach, beyond the actuator range) and a pose without a
/// stable equilibrium, naming the pose, and a machine without the elastic model (its dynamics: section).
Result<ModesJobResult> run_modes_job(const Machine& machine, const ModesJob& job);

}  // namespace pkm::pipeline
