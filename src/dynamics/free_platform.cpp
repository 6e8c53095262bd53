#include "dynamics/free_platform.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>

#include "dynamics/fixed_cholesky.hpp"

namespace pkm::dynamics {
namespace {

Error across_or_zero(int strut) {
  return make_error(ErrorCode::singular,
                    fmt::format("strut {} has zero length or is across its carriage's path", strut + 1));
}

}  // namespace

Status make_free_platform_model(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                const std::string& where, const std::string& purpose,
                                FreePlatformModel& model) {
  model.mechanism = &mechanism;
  model.parameters = &parameters;
  if (platform_twist_basis(mechanism, model.basis)) {
    model.coordinates = static_cast<int>(model.basis.cols());
    model.struts = mechanism.actuator_count();
  }
  model.base_joints_fixed = mechanism.has_distance_actuators();
  if (mechanism.actuators_are_angles()) {
    return make_error(
        ErrorCode::unsupported,
        fmt::format("{}{} needs actuators that are lengths or carriage positions in mm; this {} turns its "
                    "carriages by angles",
                    where, purpose, to_string(mechanism.type())));
  }
  if (model.struts == 0) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("{}a {} has no platform that moves freely in a fixed twist basis (its "
                                  "allowed twists turn with the pose): {} needs one",
                                  where, to_string(mechanism.type()), purpose));
  }
  // The platform body as body_motion combines it, read back into the tool frame from its state at home.
  MechanismState home;
  if (Status s = mechanism_state(mechanism, parameters, mechanism.home(), home); !s) return s;
  model.platform_kg = home.platform_kg;
  const Eigen::Matrix3d& r = home.pose.rotation;
  model.platform_com_mm = r.transpose() * home.platform_arm_mm;
  model.platform_inertia_kg_mm2 = r.transpose() * home.platform_inertia_kg_mm2 * r;
  model.strut_constants = fixed_base_strut_constants(parameters, model.struts);
  return ok_status();
}

Status free_platform_state(const FreePlatformModel& model, const Pose& pose, MechanismState& state) {
  const Mechanism& mechanism = *model.mechanism;
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  state.pose = *completed;
  state.struts = mechanism.strut_state(state.pose, state.ends, state.actuators.data(), state.twist_jacobian);
  if (state.struts != model.struts) {
    return make_error(ErrorCode::unreachable, "the platform left the mechanism's reach");
  }
  // Normalised once here for rigid_terms, all struts at once (strut by strut, a square root and divisions
  // each were a tenth of the elastic right-hand side).
  if (const int zero = set_strut_directions(state); zero >= 0) return across_or_zero(zero);
  if (model.base_joints_fixed) {
    for (int j = 0; j < state.struts; ++j) {
      state.base_first[j].setZero();
      state.base_second[j].setZero();
      state.base_moves[j] = false;
    }
    state.fixed_base_constants = model.strut_constants;
  } else {
    for (int j = 0; j < state.struts; ++j) {
      mechanism.base_joint_motion(j, state.actuators[j], state.base_first[j], state.base_second[j]);
      state.base_moves[j] = state.base_first[j].squaredNorm() > 0.0;
      const Eigen::Vector3d d = state.ends.platform_mm[j] - state.ends.base_mm[j];
      if (state.base_moves[j] && !(std::abs(d.dot(state.base_first[j])) > 0.0)) return across_or_zero(j);
    }
    set_fixed_base_constants(model.strut_constants, state);
  }
  const Eigen::Matrix3d& r = state.pose.rotation;
  state.platform_kg = model.platform_kg;
  state.platform_arm_mm = r * model.platform_com_mm;
  state.platform_inertia_kg_mm2 = r * model.platform_inertia_kg_mm2 * r.transpose();
  return ok_status();
}

bool solve_mass(const FreePlatformModel& model, const CoordinateMatrix& mass, const CoordinateVector& rhs,
                CoordinateVector& solution) {
  if (model.coordinates == 6) {
    Eigen::Matrix<double, 6, 1> fixed;
    const bool positive = cholesky_solve<6>(mass, rhs, fixed);
    solution = fixed;
    return positive;
  }
  const Eigen::LLT<CoordinateMatrix> factor(mass);
  solution = factor.solve(rhs);
  return factor.info() == Eigen::Success;
}

}  // namespace pkm::dynamics
