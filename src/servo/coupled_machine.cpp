#include "servo/coupled_machine.hpp"

#include <fmt/format.h>

#include <cmath>

#include "dynamics/elastic_equilibrium.hpp"

namespace pkm::servo {

namespace {

// Joules per N·mm.
constexpr double kJoulePerNmm = 1e-3;
// The energy accounts' weight in the integrator's error (mm per J): small, so that they never hold the step;
// they are integrals of the state, as accurate as it.
constexpr double kEnergyMmPerJoule = 1e-3;
// τ of the rates' scaling where the options give none, s.
constexpr double kCoupledTimeScaleS = 1e-3;

Error coupled_key_error(const Machine& machine, int line, const std::string& key, const std::string& what) {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}: {}: {}", machine.source, line, key, what),
               ErrorLocation{machine.source, line, 0, key}};
}

}  // namespace

// The coupled machine's equations: the platform's (elastic_model.hpp) and the drives' as auxiliary states
// [q (n), q̇ (n), F (n), input energy, dissipated energy].
struct CoupledEquations final : dynamics::PlatformRightHandSide {
  const dynamics::ElasticModel* model = nullptr;
  int drives = 0;
  bool track_energy = false;
  double smoothing_mm_s = 0.1;
  DriveVector inverse_mass = DriveVector::Zero();  ///< mm/s² per N
  DriveVector inverse_lag = DriveVector::Zero();   ///< 1/T_μ
  DriveVector coulomb = DriveVector::Zero(), breakaway = DriveVector::Zero(), stribeck = DriveVector::Zero(),
              viscous = DriveVector::Zero();
  DriveVector force_command = DriveVector::Zero();
  statics::Wrench load;
  dynamics::ElasticWorkspace workspace;
  dynamics::DriveSetpoint setpoint;
  dynamics::StrutForces forces;

  // f(q̇) = tanh(q̇/v_ε) (F_c + (F_s − F_c) e^(−(q̇/w_s)²)) + b q̇: the drive's friction, smoothed.
  double friction_N(int j, double speed) const {
    double dry = coulomb[j];
    if (stribeck[j] > 0.0) {
      const double ratio = speed / stribeck[j];
      dry += (breakaway[j] - coulomb[j]) * std::exp(-ratio * ratio);
    }
    return dry * std::tanh(speed / smoothing_mm_s) + viscous[j] * speed;
  }

  Status evaluate(double, const Pose& pose, const dynamics::CoordinateVector& rates,
                  const dynamics::AuxiliaryVector& state, dynamics::CoordinateVector& accelerations,
                  dynamics::AuxiliaryVector& state_rates) override {
    const int n = drives;
    setpoint.position_mm = state.segment(0, n);
    setpoint.rate_mm_s = state.segment(n, n);
    setpoint.load = load;
    if (Status s = elastic_accelerations(*model, pose, rates, setpoint, workspace, accelerations, &forces);
        !s)
      return s;
    double input_W = 0.0, dissipated_W = 0.0;
    for (int j = 0; j < n; ++j) {
      const double speed = state[n + j], force = state[2 * n + j];
      const double friction = friction_N(j, speed);
      const double tension = forces.force_N[j];
      state_rates[j] = speed;
      state_rates[n + j] = (force - friction + tension) * inverse_mass[j];
      state_rates[2 * n + j] = (force_command[j] - force) * inverse_lag[j];
      if (track_energy) {
        const double damping =
            tension - model->parameters->struts[j].stiffness_N_mm * forces.elongation_mm[j];
        input_W += force * speed;
        dissipated_W += friction * speed + damping * forces.elongation_rate_mm_s[j];
      }
    }
    if (track_energy) {
      // The load's power on the platform: its twist's linear part is the tool point's velocity.
      const Eigen::Matrix<double, 6, 1> twist = model->coordinates == 6
                                                    ? Eigen::Matrix<double, 6, 1>(rates)
                                                    : Eigen::Matrix<double, 6, 1>(model->basis * rates);
      input_W += load.force_N.dot(twist.head<3>()) + load.moment_Nmm.dot(twist.tail<3>());
      state_rates[3 * n] = input_W * kJoulePerNmm;
      state_rates[3 * n + 1] = dissipated_W * kJoulePerNmm;
    }
    return ok_status();
  }
};

struct CoupledMachine::Impl {
  const Machine* machine;
  DynamicsParameters parameters;  // the machine's, each strut's stiffness in series with its transmission
  dynamics::ElasticModel model;
  DriveRegulators regulators;
  dynamics::PlatformIntegrator integrator;
  CoupledEquations equations;
  CoupledOptions options;
  DriveVector mass = DriveVector::Zero();  // N/(mm/s²)
  double period_s;

  Impl(const Machine& m, const DynamicsParameters& p, const dynamics::ElasticModel& elastic,
       const LoopDesign& design, double loop_period_s, const CoupledOptions& o)
      : machine(&m),
        parameters(p),
        model(elastic),
        regulators(design, loop_period_s),
        integrator(model, o.integration, "coupled simulation"),
        options(o),
        period_s(loop_period_s) {
    model.parameters = &parameters;
  }
};

CoupledMachine::CoupledMachine(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CoupledMachine::~CoupledMachine() = default;
CoupledMachine::CoupledMachine(CoupledMachine&&) noexcept = default;
CoupledMachine& CoupledMachine::operator=(CoupledMachine&&) noexcept = default;

Result<CoupledMachine> CoupledMachine::make(const Machine& machine, const LoopDesign& design,
                                            double loop_period_s, const CoupledOptions& options) {
  const int n = design.drives;
  dynamics::ElasticModelOptions elastic_options;
  for (int j = 0; j < n; ++j) {
    elastic_options.lost_motion_mm[j] = design.channels[j].backlash;
    elastic_options.series_damping_N_s_per_mm[j] = machine.servo.drives[j].transmission_damping;
  }
  auto checked = dynamics::make_elastic_model(machine, elastic_options);  // names the machine file's keys
  if (!checked) return checked.error();
  DynamicsParameters parameters = machine.dynamics;
  for (int j = 0; j < n; ++j) {
    const double transmission = machine.servo.drives[j].transmission_stiffness;
    double& strut = parameters.struts[j].stiffness_N_mm;
    if (transmission > 0.0) strut = 1.0 / (1.0 / strut + 1.0 / transmission);
  }
  const ActuatorVector motors = motor_inertia(machine.servo, n);
  auto impl = std::make_unique<Impl>(machine, parameters, *checked, design, loop_period_s, options);
  CoupledEquations& e = impl->equations;
  e.model = &impl->model;
  e.drives = n;
  e.track_energy = options.track_energy;
  e.smoothing_mm_s = options.friction_smoothing_mm_s;
  for (int j = 0; j < n; ++j) {
    if (!(motors[j] > 0.0)) {
      return coupled_key_error(machine, machine.servo.drives[j].line,
                               fmt::format("servo.drives[{}].motor_inertia_kg_cm2", j),
                               "the machine in the loop moves each drive's motor: give its inertia and "
                               "screw_lead_mm");
    }
    const ChannelGains& c = design.channels[j];
    impl->mass[j] = motors[j];
    e.inverse_mass[j] = 1.0 / motors[j];
    e.inverse_lag[j] = 1.0 / c.lag_s;
    e.coulomb[j] = c.friction_coulomb;
    e.breakaway[j] = std::max(c.friction_static, c.friction_coulomb);
    e.stribeck[j] = c.stribeck_speed;
    e.viscous[j] = c.friction_viscous;
  }
  return CoupledMachine(std::move(impl));
}

Status CoupledMachine::reset(double time_s, const DriveVector& drive_position, const Pose& guess,
                             const statics::Wrench& load) {
  Impl& s = *impl_;
  const int n = s.equations.drives;
  const ActuatorVector held = drive_position.head(n);
  auto rest = dynamics::static_equilibrium(s.model, held, guess, load);
  if (!rest) return rest.error();
  // With lost motion the element is stretched by half the gap more, on the side its force takes it.
  ActuatorVector shifted = held;
  bool gaps = false;
  for (int j = 0; j < n; ++j) {
    const double half = 0.5 * s.model.options.lost_motion_mm[j];
    gaps = gaps || half > 0.0;
    shifted[j] += std::copysign(half, rest->strut_force_N[j]);
  }
  if (gaps) {
    rest = dynamics::static_equilibrium(s.model, shifted, rest->pose, load);
    if (!rest) return rest.error();
  }
  s.equations.load = load;
  DriveVector holding = DriveVector::Zero();
  dynamics::AuxiliaryVector state = dynamics::AuxiliaryVector::Zero(3 * n + 2);
  for (int j = 0; j < n; ++j) {
    holding[j] = -rest->strut_force_N[j];
    state[j] = held[j];
    state[2 * n + j] = holding[j];
  }
  s.equations.force_command = holding;
  dynamics::PlatformScales scales;
  scales.length_mm = s.model.mechanism->platform_size_mm();
  scales.time_scale_s = s.options.integration.rate_time_scale_s > 0.0
                            ? s.options.integration.rate_time_scale_s
                            : kCoupledTimeScaleS;
  scales.auxiliary_mm_per_unit.resize(3 * n + 2);
  for (int j = 0; j < n; ++j) {
    scales.auxiliary_mm_per_unit[j] = 1.0;
    scales.auxiliary_mm_per_unit[n + j] = scales.time_scale_s;
    // A force error counts as the elongation it makes.
    scales.auxiliary_mm_per_unit[2 * n + j] = 1.0 / s.parameters.struts[j].stiffness_N_mm;
  }
  scales.auxiliary_mm_per_unit[3 * n] = scales.auxiliary_mm_per_unit[3 * n + 1] = kEnergyMmPerJoule;
  s.integrator.start(time_s, rest->pose, dynamics::CoordinateVector::Zero(s.model.coordinates), state,
                     scales);
  s.regulators.reset(drive_position, holding);
  read_drives();
  return ok_status();
}

void CoupledMachine::set_load(const statics::Wrench& load) {
  impl_->equations.load = load;
}

Status CoupledMachine::step(const DriveVector& reference, const DriveVector& reference_speed) {
  Impl& s = *impl_;
  s.equations.force_command = s.regulators.regulate(reference, reference_speed, position_, speed_);
  if (Status moved = s.integrator.advance_exactly_to(s.integrator.time_s() + s.period_s, s.equations); !moved)
    return moved;
  read_drives();
  return ok_status();
}

void CoupledMachine::read_drives() {
  const int n = impl_->equations.drives;
  const dynamics::AuxiliaryVector state = impl_->integrator.auxiliary();
  position_.head(n) = state.segment(0, n);
  speed_.head(n) = state.segment(n, n);
  force_.head(n) = state.segment(2 * n, n);
}

double CoupledMachine::time_s() const {
  return impl_->integrator.time_s();
}
Pose CoupledMachine::pose() const {
  return impl_->integrator.pose();
}
const DriveVector& CoupledMachine::command() const {
  return impl_->regulators.command();
}
const ClampFlags& CoupledMachine::clamps() const {
  return impl_->regulators.clamps();
}
const dynamics::IntegrationCounters& CoupledMachine::counters() const {
  return impl_->integrator.counters();
}
double CoupledMachine::loop_period_s() const {
  return impl_->period_s;
}

Result<CoupledEnergy> CoupledMachine::energy() const {
  const Impl& s = *impl_;
  const int n = s.equations.drives;
  auto platform = dynamics::elastic_energy(s.model, pose(), s.integrator.rates(), position_.head(n));
  if (!platform) return platform.error();
  CoupledEnergy e;
  e.kinetic_J = platform->kinetic_J;
  e.elastic_J = platform->elastic_J;
  e.gravity_J = platform->gravity_J;
  // ½ m q̇², N/(mm/s²) · (mm/s)² = N·mm.
  for (int j = 0; j < n; ++j) e.drive_kinetic_J += 0.5 * s.mass[j] * speed_[j] * speed_[j] * kJoulePerNmm;
  const dynamics::AuxiliaryVector state = s.integrator.auxiliary();
  e.input_J = state[3 * n];
  e.dissipated_J = state[3 * n + 1];
  return e;
}

}  // namespace pkm::servo
