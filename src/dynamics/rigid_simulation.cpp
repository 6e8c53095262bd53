#include "dynamics/rigid_simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "dynamics/rigid_terms.hpp"

namespace pkm::dynamics {
namespace {

// τ of the rates' scaling where neither the settings nor a lag give one: a rate error then counts as the
// position error it makes within 10 ms, about ten servo periods.
constexpr double kDefaultTimeScaleS = 0.01;

double moving_mass_kg(const FreePlatformModel& model) {
  double mass = model.platform_kg;
  const DynamicsParameters& parameters = *model.parameters;
  for (int j = 0; j < parameters.strut_count; ++j) {
    const StrutDynamics& strut = parameters.struts[j];
    mass += strut.lower.mass_kg + strut.upper.mass_kg + strut.carriage_kg;
  }
  return std::max(mass, 1.0);
}

}  // namespace

struct RigidEquations final : PlatformRightHandSide {
  const FreePlatformModel* model = nullptr;
  const DriveCommand* command = nullptr;
  statics::Wrench load;
  MechanismState state;
  RigidTerms rigid;
  ActuatorVector command_N, actuator_rates;
  DriveResponse response;
  CoordinateVector generalised;

  Status evaluate(double time_s, const Pose& pose, const CoordinateVector& rates,
                  const AuxiliaryVector& auxiliary, CoordinateVector& accelerations,
                  AuxiliaryVector& auxiliary_rates) override {
    if (Status s = free_platform_state(*model, pose, state); !s) return s;
    const Twist twist = model->basis * rates;
    rigid_terms(state, *model->parameters, model->basis, twist, load, rigid);
    actuator_rates = state.twist_jacobian * twist;
    command->command_N(time_s, command_N);
    drive_response(*model->parameters, command_N, actuator_rates, auxiliary, response);
    // The drive pushing its coordinate up (P > 0) does power P q̇ = P (J_B ċ): its generalised force is J_Bᵀ
    // P.
    generalised =
        rigid.applied - rigid.bias +
        model->basis.transpose() * (state.twist_jacobian.transpose() * (response.force_N * kKgMmS2PerN));
    if (!solve_mass(*model, rigid.mass, generalised, accelerations)) {
      return make_error(ErrorCode::singular,
                        "the mass matrix is not positive definite (a massless platform direction)");
    }
    auxiliary_rates = response.force_rate_N_s.head(auxiliary_rates.size());
    return ok_status();
  }
};

SampledDriveCommand::SampledDriveCommand(std::vector<double> times_s, std::vector<ActuatorVector> forces_N)
    : times_s_(std::move(times_s)), forces_N_(std::move(forces_N)) {}

void SampledDriveCommand::command_N(double time_s, ActuatorVector& out) const {
  if (times_s_.empty()) {
    out.resize(0);
    return;
  }
  if (time_s <= times_s_.front()) {
    out = forces_N_.front();
    return;
  }
  if (time_s >= times_s_.back()) {
    out = forces_N_.back();
    return;
  }
  const auto after = std::upper_bound(times_s_.begin(), times_s_.end(), time_s);
  const auto k = static_cast<std::size_t>(after - times_s_.begin());
  const double span = times_s_[k] - times_s_[k - 1];
  const double share = span > 0.0 ? (time_s - times_s_[k - 1]) / span : 1.0;
  out = (1.0 - share) * forces_N_[k - 1] + share * forces_N_[k];
}

struct RigidSimulator::Impl {
  const FreePlatformModel* model;
  PlatformIntegration integration;
  PlatformIntegrator integrator;
  RigidEquations equations;
  const DriveCommand* last_command = nullptr;
  bool lagging = false;

  Impl(const FreePlatformModel& m, const PlatformIntegration& i, const statics::Wrench& load)
      : model(&m), integration(i), integrator(m, i, "rigid simulation") {
    equations.model = &m;
    equations.load = load;
    lagging = m.parameters->drive == DriveModel::first_order_lag;
  }
};

RigidSimulator::RigidSimulator(const FreePlatformModel& model, const PlatformIntegration& integration,
                               const statics::Wrench& load)
    : impl_(std::make_unique<Impl>(model, integration, load)) {}
RigidSimulator::~RigidSimulator() = default;
RigidSimulator::RigidSimulator(RigidSimulator&&) noexcept = default;
RigidSimulator& RigidSimulator::operator=(RigidSimulator&&) noexcept = default;

Status RigidSimulator::start(double time_s, const Pose& pose, const CoordinateVector& rates,
                             const ActuatorVector& initial_force_N) {
  Impl& s = *impl_;
  const FreePlatformModel& model = *s.model;
  if (rates.size() != model.coordinates) {
    return make_error(ErrorCode::bad_input, fmt::format("rigid simulation: {} rates given for {} coordinates",
                                                        rates.size(), model.coordinates));
  }
  if (s.lagging && initial_force_N.size() != model.struts) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("rigid simulation: {} initial forces given for {} drives",
                                  initial_force_N.size(), model.struts));
  }
  if (Status state = free_platform_state(model, pose, s.equations.state); !state) return state;
  PlatformScales scales;
  scales.length_mm = model.mechanism->platform_size_mm();
  scales.time_scale_s = s.integration.rate_time_scale_s;
  if (!(scales.time_scale_s > 0.0))
    scales.time_scale_s = s.lagging ? model.parameters->drive_lag_s : kDefaultTimeScaleS;
  AuxiliaryVector lag_state;
  if (s.lagging) {
    // A force error δP acting for τ on the moving mass m moves it by δP·τ²/m: the length one newton is worth.
    const double mm_per_N = kKgMmS2PerN * scales.time_scale_s * scales.time_scale_s / moving_mass_kg(model);
    scales.auxiliary_mm_per_unit = AuxiliaryVector::Constant(model.struts, mm_per_N);
    lag_state = initial_force_N;
  }
  s.integrator.start(time_s, s.equations.state.pose, rates, lag_state, scales);
  s.last_command = nullptr;
  return ok_status();
}

Status RigidSimulator::advance_to(double time_s, const DriveCommand& command) {
  Impl& s = *impl_;
  if (s.last_command != &command) {
    s.integrator.restart();
    s.last_command = &command;
  }
  s.equations.command = &command;
  return s.integrator.advance_to(time_s, s.equations);
}

double RigidSimulator::time_s() const {
  return impl_->integrator.time_s();
}
Pose RigidSimulator::pose() const {
  return impl_->integrator.pose();
}
CoordinateVector RigidSimulator::rates() const {
  return impl_->integrator.rates();
}
ActuatorVector RigidSimulator::drive_force_N(const DriveCommand& command) const {
  const Impl& s = *impl_;
  if (s.lagging) return s.integrator.auxiliary();
  MechanismState state;
  ActuatorVector command_N;
  command.command_N(s.integrator.time_s(), command_N);
  if (!free_platform_state(*s.model, s.integrator.pose(), state)) return command_N;
  const ActuatorVector rates = state.twist_jacobian * (s.model->basis * s.integrator.rates());
  DriveResponse response;
  drive_response(*s.model->parameters, command_N, rates, ActuatorVector(), response);
  return response.force_N;
}
const IntegrationCounters& RigidSimulator::counters() const {
  return impl_->integrator.counters();
}

}  // namespace pkm::dynamics
