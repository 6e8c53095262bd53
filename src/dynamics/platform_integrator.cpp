#include "dynamics/platform_integrator.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/dense_output_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <exception>
#include <functional>
#include <string>

#include "dynamics/pi_step_adjuster.hpp"

namespace pkm::dynamics {
namespace {

namespace odeint = boost::numeric::odeint;

// Tool point 3 + quaternion 4 + up to six coordinate rates + the auxiliary states: fixed size, so that
// stepping never allocates (unused components stay zero and cost no error).
constexpr int kPositionAt = 0, kQuaternionAt = 3, kRatesAt = 7, kAuxiliaryAt = 13,
              kStateSize = kAuxiliaryAt + kMaxAuxiliaryStates;
using State = std::array<double, kStateSize>;
using Stepper = odeint::runge_kutta_dopri5<State>;
using ErrorChecker = odeint::default_error_checker<double, Stepper::algebra_type, Stepper::operations_type>;
using Controller = odeint::controlled_runge_kutta<Stepper, ErrorChecker, PiStepAdjuster<double, double>>;
using DenseStepper = odeint::dense_output_runge_kutta<Controller>;

// The first step, as a fraction of τ: the controller finds its own within a few steps.
constexpr double kFirstStepOfTimeScale = 0.05;

}  // namespace

struct PlatformIntegrator::Impl {
  const FreePlatformModel* model;
  PlatformIntegration integration;
  std::string name;
  DenseStepper stepper;
  State x{};       // the state at t (interpolated within the stepper's last step)
  double t = 0.0;  // the time asked for last; the stepper may be ahead, at stepper.current_time()
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();  // the tool point at start(); x holds the offset
  PlatformScales scales;
  std::array<double, 6> rate_scale{};  // per coordinate: τ or τ·L
  std::array<double, 6> inverse_rate_scale{};
  int auxiliary_count = 0;
  PlatformRightHandSide* equations = nullptr;
  CoordinateVector rates, accelerations;
  AuxiliaryVector auxiliary, auxiliary_rates;
  Status failure = ok_status();
  IntegrationCounters counters;

  Impl(const FreePlatformModel& m, const PlatformIntegration& i, const char* n)
      : model(&m),
        integration(i),
        name(n),
        stepper(Controller(ErrorChecker(i.abs_tolerance_mm, i.rel_tolerance),
                           PiStepAdjuster<double, double>(i.max_step_s), Stepper())) {}

  Pose pose_of(const State& s) const {
    Pose p;
    p.position_mm = origin_mm + Eigen::Vector3d(s[kPositionAt], s[kPositionAt + 1], s[kPositionAt + 2]);
    const Eigen::Quaterniond q(s[kQuaternionAt], s[kQuaternionAt + 1], s[kQuaternionAt + 2],
                               s[kQuaternionAt + 3]);
    p.rotation = q.normalized().toRotationMatrix();
    return p;
  }

  void rates_of(const State& s, CoordinateVector& out) const {
    out.resize(model->coordinates);
    for (int k = 0; k < model->coordinates; ++k) out[k] = s[kRatesAt + k] * inverse_rate_scale[k];
  }

  void auxiliary_of(const State& s, AuxiliaryVector& out) const {
    out.resize(auxiliary_count);
    for (int k = 0; k < auxiliary_count; ++k) out[k] = s[kAuxiliaryAt + k] / scales.auxiliary_mm_per_unit[k];
  }

  // dx/dt. A failure is kept and the derivative zeroed; advance_to() stops after the step and reports it
  // (the integrator's interface has no error path).
  void derivative(const State& s, State& ds, double time_s) {
    ++counters.evaluations;
    ds.fill(0.0);
    if (!failure) return;
    rates_of(s, rates);
    auxiliary_of(s, auxiliary);
    auxiliary_rates.resize(auxiliary_count);
    const Pose pose = pose_of(s);
    if (Status status = equations->evaluate(time_s, pose, rates, auxiliary, accelerations, auxiliary_rates);
        !status) {
      failure = status;
      return;
    }
    // The basis of six coordinates is the identity (platform_twist_basis).
    const Eigen::Matrix<double, 6, 1> twist = model->coordinates == 6
                                                  ? Eigen::Matrix<double, 6, 1>(rates)
                                                  : Eigen::Matrix<double, 6, 1>(model->basis * rates);
    for (int i = 0; i < 3; ++i) ds[kPositionAt + i] = twist[i];
    // q̇ = ½ (0, ω) ⊗ q: ẇ = −½ ω·v, v̇ = ½ (w ω + ω × v); linear in q, so the scale L carries through.
    const Eigen::Vector3d omega = twist.tail<3>();
    const double w = s[kQuaternionAt];
    const Eigen::Vector3d v(s[kQuaternionAt + 1], s[kQuaternionAt + 2], s[kQuaternionAt + 3]);
    const Eigen::Vector3d v_rate = 0.5 * (w * omega + omega.cross(v));
    ds[kQuaternionAt] = -0.5 * omega.dot(v);
    for (int i = 0; i < 3; ++i) ds[kQuaternionAt + 1 + i] = v_rate[i];
    for (int k = 0; k < model->coordinates; ++k) ds[kRatesAt + k] = accelerations[k] * rate_scale[k];
    for (int k = 0; k < auxiliary_count; ++k)
      ds[kAuxiliaryAt + k] = auxiliary_rates[k] * scales.auxiliary_mm_per_unit[k];
  }

  // advance_to / advance_exactly_to: steps until `time_s` is covered; `exact`: the last step shortened to end
  // on it and the stepper restarted there.
  Status advance(double time_s, PlatformRightHandSide& rhs, bool exact) {
    if (time_s < t) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: asked for {:.6f} s, before {:.6f} s", name, time_s, t));
    }
    equations = &rhs;
    failure = ok_status();
    auto system = [this](const State& state, State& rate, double at) { derivative(state, rate, at); };
    // Within this much of `time_s` a step counts as ending on it (rounding of the time sum).
    const double close_s = 1e-12 * std::max(1.0, std::abs(time_s));
    double proposed_s = stepper.current_time_step();
    long steps = 0;
    try {
      while (stepper.current_time() < time_s - (exact ? close_s : 0.0)) {
        if (++steps > integration.max_steps_per_advance) {
          return make_error(ErrorCode::not_converged,
                            fmt::format("{}: more than {} steps from {:.6f} s to {:.6f} s", name,
                                        integration.max_steps_per_advance, t, time_s));
        }
        if (exact && stepper.current_time() + stepper.current_time_step() > time_s) {
          proposed_s = stepper.current_time_step();
          stepper.initialize(stepper.current_state(), stepper.current_time(),
                             time_s - stepper.current_time());
        }
        stepper.do_step(std::ref(system));
        if (!failure) {
          return Error{failure.error().code, fmt::format("{} at {:.6f} s: {}", name, stepper.current_time(),
                                                         failure.error().message)};
        }
        ++counters.accepted_steps;
      }
    } catch (const std::exception& e) {  // Odeint's step-size control gave up: the step size collapsed
      return make_error(ErrorCode::not_converged,
                        fmt::format("{} near {:.6f} s: {}", name, stepper.current_time(), e.what()));
    }
    if (exact) {
      x = stepper.current_state();
      t = time_s;
      stepper.initialize(x, t, std::max(proposed_s, stepper.current_time_step()));
      return ok_status();
    }
    stepper.calc_state(time_s, x);  // Dormand–Prince's own interpolant within the last step
    t = time_s;
    return ok_status();
  }
};

PlatformIntegrator::PlatformIntegrator(const FreePlatformModel& model, const PlatformIntegration& integration,
                                       const char* name)
    : impl_(std::make_unique<Impl>(model, integration, name)) {}
PlatformIntegrator::~PlatformIntegrator() = default;
PlatformIntegrator::PlatformIntegrator(PlatformIntegrator&&) noexcept = default;
PlatformIntegrator& PlatformIntegrator::operator=(PlatformIntegrator&&) noexcept = default;

void PlatformIntegrator::start(double time_s, const Pose& pose, const CoordinateVector& rates,
                               const AuxiliaryVector& auxiliary, const PlatformScales& scales) {
  Impl& s = *impl_;
  const FreePlatformModel& model = *s.model;
  s.scales = scales;
  s.auxiliary_count = static_cast<int>(scales.auxiliary_mm_per_unit.size());
  for (int k = 0; k < model.coordinates; ++k) {
    const bool angular = model.basis.col(k).tail<3>().squaredNorm() > 0.0;
    s.rate_scale[k] = scales.time_scale_s * (angular ? scales.length_mm : 1.0);
    s.inverse_rate_scale[k] = 1.0 / s.rate_scale[k];
  }
  s.origin_mm = pose.position_mm;
  s.x.fill(0.0);
  const Eigen::Quaterniond q(pose.rotation);
  s.x[kQuaternionAt] = q.w() * scales.length_mm;
  s.x[kQuaternionAt + 1] = q.x() * scales.length_mm;
  s.x[kQuaternionAt + 2] = q.y() * scales.length_mm;
  s.x[kQuaternionAt + 3] = q.z() * scales.length_mm;
  for (int k = 0; k < model.coordinates; ++k) s.x[kRatesAt + k] = rates[k] * s.rate_scale[k];
  for (int k = 0; k < s.auxiliary_count; ++k)
    s.x[kAuxiliaryAt + k] = auxiliary[k] * scales.auxiliary_mm_per_unit[k];
  s.t = time_s;
  double first_step = kFirstStepOfTimeScale * scales.time_scale_s;
  if (s.integration.max_step_s > 0.0) first_step = std::min(first_step, s.integration.max_step_s);
  s.stepper.initialize(s.x, time_s, first_step);
  s.counters = {};
}

void PlatformIntegrator::restart() {
  Impl& s = *impl_;
  s.stepper.initialize(s.x, s.t, s.stepper.current_time_step());
}

Status PlatformIntegrator::advance_to(double time_s, PlatformRightHandSide& equations) {
  return impl_->advance(time_s, equations, false);
}

Status PlatformIntegrator::advance_exactly_to(double time_s, PlatformRightHandSide& equations) {
  return impl_->advance(time_s, equations, true);
}

double PlatformIntegrator::time_s() const {
  return impl_->t;
}
Pose PlatformIntegrator::pose() const {
  return impl_->pose_of(impl_->x);
}
CoordinateVector PlatformIntegrator::rates() const {
  CoordinateVector r;
  impl_->rates_of(impl_->x, r);
  return r;
}
AuxiliaryVector PlatformIntegrator::auxiliary() const {
  AuxiliaryVector a;
  impl_->auxiliary_of(impl_->x, a);
  return a;
}
const IntegrationCounters& PlatformIntegrator::counters() const {
  return impl_->counters;
}
const PlatformScales& PlatformIntegrator::scales() const {
  return impl_->scales;
}

}  // namespace pkm::dynamics
