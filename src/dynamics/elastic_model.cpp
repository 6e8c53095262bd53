#include "dynamics/elastic_model.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "core/wide_kernels.hpp"
#include "dynamics/fixed_cholesky.hpp"

namespace pkm::dynamics {
namespace {

constexpr double kJoulePerKgMm2S2 = 1e-6;  // kg·mm²/s² → J

// What the elastic model needs beyond a free platform: every strut's elastic element.
Status check_struts(const DynamicsParameters& parameters, const ElasticModel& model,
                    const std::string& where) {
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
  model.options = options;
  if (Status s = make_free_platform_model(mechanism, parameters, where, "the elastic model", model); !s)
    return s.error();
  if (Status checked = check_struts(parameters, model, where); !checked) return checked.error();
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
      // β ẋ |ẋ| (Smirnov 2019, §4.2): C¹ at ẋ = 0, so it needs no smoothing.
      return beta * rate_mm_s * std::abs(rate_mm_s);
    case StrutDamping::coulomb:
      return beta * std::tanh(rate_mm_s / options.coulomb_smoothing_mm_s);
  }
  return 0.0;
}

namespace {

// The element's elongation past the lost motion (half the gap either way), and whether it is engaged.
double engaged_elongation_mm(double elongation_mm, double gap_mm, bool& engaged) {
  const double half = 0.5 * gap_mm;
  engaged = std::abs(elongation_mm) > half;
  return engaged ? elongation_mm - std::copysign(half, elongation_mm) : 0.0;
}

// The elastic elements' forces (kg·mm/s², tension positive) from the actuators' rates; fills `forces` when
// given.
template <class Rates, class Forces>
void element_forces(const ElasticModel& model, const MechanismState& state, const Rates& actuator_rates,
                    const DriveSetpoint& drives, Forces& force_kg_mm_s2, StrutForces* forces) {
  const DynamicsParameters& parameters = *model.parameters;
  const int n = model.struts;
  if (forces) {
    forces->elongation_mm.resize(n);
    forces->elongation_rate_mm_s.resize(n);
    forces->force_N.resize(n);
  }
  for (int j = 0; j < n; ++j) {
    const StrutDynamics& strut = parameters.struts[j];
    bool engaged = true;
    const double elongation = engaged_elongation_mm(state.actuators[j] - drives.position_mm[j],
                                                    model.options.lost_motion_mm[j], engaged);
    const double elongation_rate = engaged ? actuator_rates[j] - drives.rate_mm_s[j] : 0.0;
    const double force_N = strut.stiffness_N_mm * elongation +
                           damping_force_N(strut, elongation_rate, model.options) +
                           model.options.series_damping_N_s_per_mm[j] * elongation_rate;
    force_kg_mm_s2[j] = force_N * kKgMmS2PerN;
    if (forces) {
      forces->elongation_mm[j] = elongation;
      forces->elongation_rate_mm_s[j] = elongation_rate;
      forces->force_N[j] = force_N;
    }
  }
}

// The six-coordinate mass solve (its factors overwrite `mass`), and a copy of it compiled for AVX2 with fused
// multiply–add (core/wide_kernels.hpp).
inline bool solve_six(Eigen::Matrix<double, 6, 6>& mass, const Twist& rhs, Twist& solution) {
  return cholesky_solve_in_place<6>(mass, rhs, solution);
}
#if PKM_HAS_WIDE_KERNELS
PKM_WIDE_KERNEL bool solve_six_wide(Eigen::Matrix<double, 6, 6>& mass, const Twist& rhs, Twist& solution) {
  return solve_six(mass, rhs, solution);
}
#endif

}  // namespace

Status elastic_accelerations(const ElasticModel& model, const Pose& pose, const CoordinateVector& rates,
                             const DriveSetpoint& drives, ElasticWorkspace& workspace,
                             CoordinateVector& accelerations, StrutForces* forces) {
  if (Status s = free_platform_state(model, pose, workspace.state); !s) return s;
  const MechanismState& state = workspace.state;
  // M c̈ = applied − bias − J_Bᵀ F: a stretched element (F > 0) pulls B towards A, against a_j's growth. J_B
  // row j · ċ = ȧ_j: the twist Jacobian is the actuators' gradient along twists (mechanism.hpp).
  bool positive = false;
  if (model.struts == 6 && model.coordinates == 6) {
    // Six struts in the platform's own twist (the basis is the identity): the same in fixed sizes, which
    // Eigen writes out (a third of this function's time with run-time sizes).
    // No projection and only M's lower triangle, which the solve reads (and overwrites with its factors).
    const Twist twist = rates;
    TwistRigidTerms& rigid = workspace.twist_rigid;
    twist_rigid_terms(state, *model.parameters, twist, drives.load, rigid);
    const Eigen::Map<const Eigen::Matrix<double, 6, 6>> jacobian(state.twist_jacobian.data());
    const Twist actuator_rates = jacobian * twist;
    Twist force_kg_mm_s2;
    element_forces(model, state, actuator_rates, drives, force_kg_mm_s2, forces);
    const Twist generalised = rigid.applied - rigid.bias - jacobian.transpose() * force_kg_mm_s2;
    Twist solution;
#if PKM_HAS_WIDE_KERNELS
    positive = wide_kernels_enabled() ? solve_six_wide(rigid.mass.lower, generalised, solution)
                                      : solve_six(rigid.mass.lower, generalised, solution);
#else
    positive = solve_six(rigid.mass.lower, generalised, solution);
#endif
    accelerations = solution;
  } else {
    const Twist twist = model.basis * rates;
    rigid_terms(state, *model.parameters, model.basis, twist, drives.load, workspace.rigid);
    const ActuatorVector actuator_rates = state.twist_jacobian * twist;
    ActuatorVector force_kg_mm_s2(model.struts);
    element_forces(model, state, actuator_rates, drives, force_kg_mm_s2, forces);
    const CoordinateVector generalised =
        workspace.rigid.applied - workspace.rigid.bias -
        model.basis.transpose() * (state.twist_jacobian.transpose() * force_kg_mm_s2);
    positive = solve_mass(model, workspace.rigid.mass, generalised, accelerations);
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
    bool engaged = true;
    const double elongation = engaged_elongation_mm(state.actuators[j] - drive_position_mm[j],
                                                    model.options.lost_motion_mm[j], engaged);
    // ½ c δl², N/mm · mm² = N·mm = 10⁻³ J.
    e.elastic_J += 0.5 * model.parameters->struts[j].stiffness_N_mm * elongation * elongation * 1e-3;
  }
  return e;
}

}  // namespace pkm::dynamics
