#include "pipeline/modes_job.hpp"

#include <array>

#include "core/rotation.hpp"
#include "core/units.hpp"

namespace pkm::pipeline {
namespace {

/// The twist component each basis coordinate moves most.
std::vector<std::string> mode_coordinate_names(const TwistBasis& basis) {
  static const std::array<const char*, 6> kNames = {"x_mm", "y_mm", "z_mm", "rx_rad", "ry_rad", "rz_rad"};
  std::vector<std::string> names;
  for (int k = 0; k < basis.cols(); ++k) {
    int row = 0;
    basis.col(k).cwiseAbs().maxCoeff(&row);
    names.emplace_back(kNames[static_cast<std::size_t>(row)]);
  }
  return names;
}

Error modes_pose_error(const ModesJob& job, Error error) {
  if (!job.pose_name.empty()) error.message = job.pose_name + ": " + error.message;
  return error;
}

}  // namespace

Result<ModesJobResult> run_modes_job(const Machine& machine, const ModesJob& job) {
  // The drives must be able to hold the pose: their range, as every other command checks it.
  auto actuators = machine.mechanism->inverse(job.pose);
  Status in_range = actuators ? check_actuator_range(machine, *actuators) : Status(actuators.error());
  if (!in_range) return modes_pose_error(job, in_range.error());
  auto model = dynamics::make_elastic_model(machine);
  if (!model) return model.error();
  auto modes = dynamics::natural_modes(*model, job.pose);
  if (!modes) return modes_pose_error(job, modes.error());
  ModesJobResult out{std::move(*modes), mode_coordinate_names(model->basis), Eigen::Vector3d::Zero(), 0.0};
  const Pose& equilibrium = out.modes.equilibrium.pose;
  out.static_deflection_mm = equilibrium.position_mm - job.pose.position_mm;
  out.static_rotation_deg = deg_from_rad(
      rotation_vector_from_rotation(equilibrium.rotation * job.pose.rotation.transpose()).norm());
  return out;
}

}  // namespace pkm::pipeline
