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
// stepping never allocates (unused components stay zero and cost no error). Two sizes: up to six auxiliary
// states (the rigid and elastic models: every step's vector operations run over 19 components), and up to
// kMaxAuxiliaryStates (the machine in the servo loops).
constexpr int kPositionAt = 0, kQuaternionAt = 3, kRatesAt = 7, kAuxiliaryAt = 13;
constexpr int kSmallAuxiliary = 6;

template <int Size>
struct Engine {
  using State = std::array<double, Size>;
  using Stepper = odeint::runge_kutta_dopri5<State>;
  using ErrorChecker = odeint::default_error_checker<double, typename Stepper::algebra_type,
                                                     typename Stepper::operations_type>;
  using Controller = odeint::controlled_runge_kutta<Stepper, ErrorChecker, PiStepAdjuster<double, double>>;
  using DenseStepper = odeint::dense_output_runge_kutta<Controller>;
};

// The first step, as a fraction of τ: the controller finds its own within a few steps.
constexpr double kFirstStepOfTimeScale = 0.05;

}  // namespace

// What PlatformIntegrator does, for a state of either size.
struct PlatformIntegrator::Impl {
  virtual ~Impl() = default;
  virtual void start(double time_s, const Pose& pose, const CoordinateVector& rates,
                     const AuxiliaryVector& auxiliary, const PlatformScales& scales) = 0;
  virtual void restart() = 0;
  virtual Status advance(double time_s, PlatformRightHandSide& rhs, bool exact) = 0;
  virtual double time_s() const = 0;
  virtual Pose pose() const = 0;
  virtual CoordinateVector rates() const = 0;
  virtual AuxiliaryVector auxiliary() const = 0;
  virtual const IntegrationCounters& counters() const = 0;
  virtual const PlatformScales& scales() const = 0;
};

namespace {

template <int Size>
struct SizedIntegrator final : PlatformIntegrator::Impl {
  using State = typename Engine<Size>::State;
  using Stepper = typename Engine<Size>::Stepper;
  using ErrorChecker = typename Engine<Size>::ErrorChecker;
  using Controller = typename Engine<Size>::Controller;
  using DenseStepper = typename Engine<Size>::DenseStepper;

  const FreePlatformModel* model;
  PlatformIntegration integration;
  std::string name;
  DenseStepper stepper;
  State x{};       // the state at t (interpolated within the stepper's last step)
  double t = 0.0;  // the time asked for last; the stepper may be ahead, at stepper.current_time()
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();  // the tool point at start(); x holds the offset
  PlatformScales scales_;
  std::array<double, 6> rate_scale{};  // per coordinate: τ or τ·L
  std::array<double, 6> inverse_rate_scale{};
  int auxiliary_count = 0;
  PlatformRightHandSide* equations = nullptr;
  CoordinateVector rate_buffer, accelerations;
  AuxiliaryVector auxiliary_buffer, auxiliary_rates;
  Status failure = ok_status();
  IntegrationCounters counters_;

  SizedIntegrator(const FreePlatformModel& m, const PlatformIntegration& i, const std::string& n)
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
    for (int k = 0; k < auxiliary_count; ++k) out[k] = s[kAuxiliaryAt + k] / scales_.auxiliary_mm_per_unit[k];
  }

  // dx/dt. A failure is kept and the derivative zeroed; advance_to() stops after the step and reports it
  // (the integrator's interface has no error path).
  void derivative(const State& s, State& ds, double time_s) {
    ++counters_.evaluations;
    ds.fill(0.0);
    if (!failure) return;
    rates_of(s, rate_buffer);
    auxiliary_of(s, auxiliary_buffer);
    auxiliary_rates.resize(auxiliary_count);
    const Pose pose = pose_of(s);
    if (Status status =
            equations->evaluate(time_s, pose, rate_buffer, auxiliary_buffer, accelerations, auxiliary_rates);
        !status) {
      failure = status;
      return;
    }
    // The basis of six coordinates is the identity (platform_twist_basis).
    const Eigen::Matrix<double, 6, 1> twist = model->coordinates == 6
                                                  ? Eigen::Matrix<double, 6, 1>(rate_buffer)
                                                  : Eigen::Matrix<double, 6, 1>(model->basis * rate_buffer);
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
      ds[kAuxiliaryAt + k] = auxiliary_rates[k] * scales_.auxiliary_mm_per_unit[k];
  }

  // advance_to / advance_exactly_to: steps until `time_s` is covered; `exact`: the last step shortened to end
  // on it and the stepper restarted there.
  Status advance(double time_s, PlatformRightHandSide& rhs, bool exact) override {
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
        ++counters_.accepted_steps;
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

  void start(double time_s, const Pose& pose, const CoordinateVector& start_rates,
             const AuxiliaryVector& start_auxiliary, const PlatformScales& scales) override {
    const FreePlatformModel& m = *model;
    scales_ = scales;
    auxiliary_count = static_cast<int>(scales.auxiliary_mm_per_unit.size());
    for (int k = 0; k < m.coordinates; ++k) {
      const bool angular = m.basis.col(k).tail<3>().squaredNorm() > 0.0;
      rate_scale[k] = scales.time_scale_s * (angular ? scales.length_mm : 1.0);
      inverse_rate_scale[k] = 1.0 / rate_scale[k];
    }
    origin_mm = pose.position_mm;
    x.fill(0.0);
    const Eigen::Quaterniond q(pose.rotation);
    x[kQuaternionAt] = q.w() * scales.length_mm;
    x[kQuaternionAt + 1] = q.x() * scales.length_mm;
    x[kQuaternionAt + 2] = q.y() * scales.length_mm;
    x[kQuaternionAt + 3] = q.z() * scales.length_mm;
    for (int k = 0; k < m.coordinates; ++k) x[kRatesAt + k] = start_rates[k] * rate_scale[k];
    for (int k = 0; k < auxiliary_count; ++k)
      x[kAuxiliaryAt + k] = start_auxiliary[k] * scales.auxiliary_mm_per_unit[k];
    t = time_s;
    double first_step = kFirstStepOfTimeScale * scales.time_scale_s;
    if (integration.max_step_s > 0.0) first_step = std::min(first_step, integration.max_step_s);
    stepper.initialize(x, time_s, first_step);
    counters_ = {};
  }

  void restart() override { stepper.initialize(x, t, stepper.current_time_step()); }
  double time_s() const override { return t; }
  Pose pose() const override { return pose_of(x); }
  CoordinateVector rates() const override {
    CoordinateVector r;
    rates_of(x, r);
    return r;
  }
  AuxiliaryVector auxiliary() const override {
    AuxiliaryVector a;
    auxiliary_of(x, a);
    return a;
  }
  const IntegrationCounters& counters() const override { return counters_; }
  const PlatformScales& scales() const override { return scales_; }
};

}  // namespace

PlatformIntegrator::PlatformIntegrator(const FreePlatformModel& model, const PlatformIntegration& integration,
                                       const char* name)
    : model_(&model),
      integration_(integration),
      name_(name),
      impl_(std::make_unique<SizedIntegrator<kAuxiliaryAt + kSmallAuxiliary>>(model, integration, name)) {}
PlatformIntegrator::~PlatformIntegrator() = default;
PlatformIntegrator::PlatformIntegrator(PlatformIntegrator&&) noexcept = default;
PlatformIntegrator& PlatformIntegrator::operator=(PlatformIntegrator&&) noexcept = default;

void PlatformIntegrator::start(double time_s, const Pose& pose, const CoordinateVector& rates,
                               const AuxiliaryVector& auxiliary, const PlatformScales& scales) {
  // The larger state only for models that need it (made here, never while integrating).
  if (scales.auxiliary_mm_per_unit.size() > kSmallAuxiliary && !large_) {
    impl_ =
        std::make_unique<SizedIntegrator<kAuxiliaryAt + kMaxAuxiliaryStates>>(*model_, integration_, name_);
    large_ = true;
  }
  impl_->start(time_s, pose, rates, auxiliary, scales);
}

void PlatformIntegrator::restart() {
  impl_->restart();
}

Status PlatformIntegrator::advance_to(double time_s, PlatformRightHandSide& equations) {
  return impl_->advance(time_s, equations, false);
}

Status PlatformIntegrator::advance_exactly_to(double time_s, PlatformRightHandSide& equations) {
  return impl_->advance(time_s, equations, true);
}

double PlatformIntegrator::time_s() const {
  return impl_->time_s();
}
Pose PlatformIntegrator::pose() const {
  return impl_->pose();
}
CoordinateVector PlatformIntegrator::rates() const {
  return impl_->rates();
}
AuxiliaryVector PlatformIntegrator::auxiliary() const {
  return impl_->auxiliary();
}
const IntegrationCounters& PlatformIntegrator::counters() const {
  return impl_->counters();
}
const PlatformScales& PlatformIntegrator::scales() const {
  return impl_->scales();
}

}  // namespace pkm::dynamics
