#include "dynamics/elastic_model.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "dynamics/fixed_cholesky.hpp"

namespace pkm::dynamics {
namespace {

constexpr double kJoulePerKgMm2S2 = 1e-6;  // kg·mm²/s² → J

Status check_parts(const Mechanism& mechanism, const DynamicsParameters& parameters,
                   const ElasticModel& model, const std::string& where) {
  if (mechanism.actuators_are_angles()) {
    return make_error(
        ErrorCode::unsupported,
        fmt::format("{}the elastic model needs actuators that are lengths or carriage positions "
                    "in mm; this {} turns its carriages by angles",
                    where, to_string(mechanism.type())));
  }
  if (model.struts == 0) {
    return make_error(
        ErrorCode::unsupported,
        fmt::format("{}a {} has no platform that moves freely in a fixed twist basis (its allowed "
                    "twists turn with the pose): the elastic model needs one",
                    where, to_string(mechanism.type())));
  }
  if (parameters.strut_count != model.struts) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}dynamics.struts: not given: the elastic model needs the stiffness_N_mm of "
                    "each of the {} struts",
                    where, model.struts));
  }
  for (int j = 0; j < model.struts; ++j) {
    if (!(parameters.struts[j].stiffness_N_mm > 0.0)) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("{}dynamics.struts.stiffness_N_mm: not given for strut {}: the elastic model "
                      "needs every strut's elastic element",
                      where, j + 1));
    }
  }
  return ok_status();
}

Result<ElasticModel> make_model(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                const ElasticModelOptions& options, const std::string& where) {
  ElasticModel model;
  model.mechanism = &mechanism;
  model.parameters = &parameters;
  model.options = options;
  if (platform_twist_basis(mechanism, model.basis)) {
    model.coordinates = static_cast<int>(model.basis.cols());
    model.struts = mechanism.actuator_count();
  }
  if (Status checked = check_parts(mechanism, parameters, model, where); !checked) return checked.error();
  // The platform body as body_motion combines it, read back into the tool frame from its state at home.
  MechanismState home;
  if (Status s = mechanism_state(mechanism, parameters, mechanism.home(), home); !s) return s.error();
  model.platform_kg = home.platform_kg;
  const Eigen::Matrix3d& r = home.pose.rotation;
  model.platform_com_mm = r.transpose() * home.platform_arm_mm;
  model.platform_inertia_kg_mm2 = r.transpose() * home.platform_inertia_kg_mm2 * r;
  if (!(options.coulomb_smoothing_mm_s > 0.0)) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("Coulomb smoothing speed must be positive, got {} mm/s", options.coulomb_smoothing_mm_s));
  }
  return model;
}

}  // namespace

Result<ElasticModel> make_elastic_model(const Machine& machine, const ElasticModelOptions& options) {
  if (!machine.dynamics.given()) {
    return Error{
        ErrorCode::bad_input,
        fmt::format("{}: the machine file has no dynamics: section (masses, inertias and the struts' "
                    "stiffness_N_mm, docs/machine-file.md): the elastic model needs it",
                    machine.source),
        ErrorLocation{machine.source, 0, 0, "dynamics"}};
  }
  const std::string where = fmt::format("{}:{}: ", machine.source, machine.dynamics.line);
  auto model = make_model(*machine.mechanism, machine.dynamics, options, where);
  if (!model) {
    Error located = model.error();
    located.location = ErrorLocation{machine.source, machine.dynamics.line, 0, "dynamics.struts"};
    return located;
  }
  return model;
}

Result<ElasticModel> make_elastic_model(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                        const ElasticModelOptions& options) {
  return make_model(mechanism, parameters, options, "");
}

double damping_force_N(const StrutDynamics& strut, double rate_mm_s, const ElasticModelOptions& options) {
  const double beta = strut.damping_coefficient;
  switch (strut.damping) {
    case StrutDamping::none:
      return 0.0;
    case StrutDamping::viscous:
      return beta * rate_mm_s;
    case StrutDamping::quadratic:
      // β ẋ |ẋ| (spec ch4 §4.5): C¹ at ẋ = 0, so it needs no smoothing (§6.8).
      return beta * rate_mm_s * std::abs(rate_mm_s);
    case StrutDamping::coulomb:
      return beta * std::tanh(rate_mm_s / options.coulomb_smoothing_mm_s);
  }
  return 0.0;
}

Status elastic_state(const ElasticModel& model, const Pose& pose, MechanismState& state) {
  const Mechanism& mechanism = *model.mechanism;
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  state.pose = *completed;
  state.struts = mechanism.strut_ends(state.pose, state.ends);
  if (state.struts != model.struts || !mechanism.actuator_values(state.pose, state.actuators.data()) ||
      !mechanism.twist_jacobian(state.pose, state.twist_jacobian)) {
    return make_error(ErrorCode::unreachable, "elastic model: the platform left the mechanism's reach");
  }
  for (int j = 0; j < state.struts; ++j) {
    const Eigen::Vector3d d = state.ends.platform_mm[j] - state.ends.base_mm[j];
    mechanism.base_joint_motion(j, state.actuators[j], state.base_first[j], state.base_second[j]);
    state.base_moves[j] = state.base_first[j].squaredNorm() > 0.0;
    if (!(d.squaredNorm() > 0.0) || (state.base_moves[j] && !(std::abs(d.dot(state.base_first[j])) > 0.0))) {
      return make_error(
          ErrorCode::singular,
          fmt::format("elastic model: strut {} has zero length or is across its carriage's path", j + 1));
    }
  }
  const Eigen::Matrix3d& r = state.pose.rotation;
  state.platform_kg = model.platform_kg;
  state.platform_arm_mm = r * model.platform_com_mm;
  state.platform_inertia_kg_mm2 = r * model.platform_inertia_kg_mm2 * r.transpose();
  return ok_status();
}

Status elastic_accelerations(const ElasticModel& model, const Pose& pose, const CoordinateVector& rates,
                             const DriveSetpoint& drives, ElasticWorkspace& workspace,
                             CoordinateVector& accelerations, StrutForces* forces) {
  const DynamicsParameters& parameters = *model.parameters;
  if (Status s = elastic_state(model, pose, workspace.state); !s) return s;
  const MechanismState& state = workspace.state;
  const Twist twist = model.basis * rates;
  rigid_terms(state, parameters, model.basis, twist, {}, workspace.rigid);
  const int n = model.struts;
  // J_B row j · ċ = ȧ_j: the twist Jacobian is the actuators' gradient along twists (mechanism.hpp).
  const ActuatorVector actuator_rates = state.twist_jacobian * twist;
  ActuatorVector force_kg_mm_s2(n);
  if (forces) {
    forces->elongation_mm.resize(n);
    forces->elongation_rate_mm_s.resize(n);
    forces->force_N.resize(n);
  }
  for (int j = 0; j < n; ++j) {
    const StrutDynamics& strut = parameters.struts[j];
    const double elongation = state.actuators[j] - drives.position_mm[j];
    const double elongation_rate = actuator_rates[j] - drives.rate_mm_s[j];
    const double force_N =
        strut.stiffness_N_mm * elongation + damping_force_N(strut, elongation_rate, model.options);
    force_kg_mm_s2[j] = force_N * kKgMmS2PerN;
    if (forces) {
      forces->elongation_mm[j] = elongation;
      forces->elongation_rate_mm_s[j] = elongation_rate;
      forces->force_N[j] = force_N;
    }
  }
  // M c̈ = applied − bias − J_Bᵀ F: a stretched element (F > 0) pulls B towards A, against a_j's growth.
  const CoordinateVector generalised =
      workspace.rigid.applied - workspace.rigid.bias -
      model.basis.transpose() * (state.twist_jacobian.transpose() * force_kg_mm_s2);
  // The free platform's 6 × 6 by the fixed-size solve (fixed_cholesky.hpp), the planar ones by Eigen's.
  bool positive = false;
  if (model.coordinates == 6) {
    Eigen::Matrix<double, 6, 1> solution;
    positive = cholesky_solve<6>(workspace.rigid.mass, generalised, solution);
    accelerations = solution;
  } else {
    const Eigen::LLT<CoordinateMatrix> mass(workspace.rigid.mass);
    positive = mass.info() == Eigen::Success;
    accelerations = mass.solve(generalised);
  }
  if (!positive) {
    return make_error(
        ErrorCode::singular,
        "elastic model: the mass matrix is not positive definite (a massless platform direction)");
  }
  return ok_status();
}

CoordinateMatrix material_stiffness(const ElasticModel& model, const MechanismState& state) {
  const JacobianMatrix drive_jacobian = state.twist_jacobian * model.basis;
  ActuatorVector stiffness_kg_s2(model.struts);
  for (int j = 0; j < model.struts; ++j)
    stiffness_kg_s2[j] = model.parameters->struts[j].stiffness_N_mm * kKgMmS2PerN;
  return drive_jacobian.transpose() * stiffness_kg_s2.asDiagonal() * drive_jacobian;
}

Result<ElasticEnergy> elastic_energy(const ElasticModel& model, const Pose& pose,
                                     const CoordinateVector& rates, const ActuatorVector& drive_position_mm) {
  MechanismState state;
  if (Status s = mechanism_state(*model.mechanism, *model.parameters, pose, state); !s) return s.error();
  ElasticEnergy e;
  const Twist twist = model.basis * rates;
  e.kinetic_J = kinetic_energy(state, *model.parameters, body_velocities(state, *model.parameters, twist)) *
                kJoulePerKgMm2S2;
  e.gravity_J = gravity_potential(state, *model.parameters) * kJoulePerKgMm2S2;
  for (int j = 0; j < model.struts; ++j) {
    const double elongation = state.actuators[j] - drive_position_mm[j];
    // ½ c δl², N/mm · mm² = N·mm = 10⁻³ J.
    e.elastic_J += 0.5 * model.parameters->struts[j].stiffness_N_mm * elongation * elongation * 1e-3;
  }
  return e;
}

}  // namespace pkm::dynamics
