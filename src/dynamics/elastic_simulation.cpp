#include "dynamics/elastic_simulation.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/dense_output_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <exception>
#include <functional>

namespace pkm::dynamics {
namespace {

namespace odeint = boost::numeric::odeint;

// Tool point 3 + quaternion 4 + up to six coordinate rates: fixed size, so that stepping never allocates.
constexpr int kPositionAt = 0, kQuaternionAt = 3, kRatesAt = 7, kStateSize = 13;
using State = std::array<double, kStateSize>;
using Stepper = odeint::runge_kutta_dopri5<State>;
using DenseStepper = odeint::result_of::make_dense_output<Stepper>::type;

// Where no stiffness tells the time scale (a model whose mass matrix fails at the start, which start() then
// reports anyway): a millisecond.
constexpr double kFallbackTimeScaleS = 1e-3;
// The first step, as a fraction of τ: the controller finds its own within a few steps.
constexpr double kFirstStepOfTimeScale = 0.05;

}  // namespace

struct ElasticSimulator::Impl {
  const ElasticModel* model;
  ElasticIntegration integration;
  DenseStepper stepper;
  State x{};       // the state at t (interpolated within the stepper's last step)
  double t = 0.0;  // the time asked for last; the stepper may be ahead, at stepper.current_time()
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();  // the tool point at start(); x holds the offset
  double length_mm = 1.0;                               // L
  double time_scale_s = kFallbackTimeScaleS;            // τ
  std::array<double, 6> rate_scale{};                   // per coordinate: τ or τ·L
  const DriveMotion* drives = nullptr;
  const DriveMotion* last_drives = nullptr;
  ElasticWorkspace workspace;
  DriveSetpoint setpoint;
  CoordinateVector rates, accelerations;
  Status failure = ok_status();
  IntegrationCounters counters;

  Impl(const ElasticModel& m, const ElasticIntegration& i)
      : model(&m),
        integration(i),
        stepper(odeint::make_dense_output(i.abs_tolerance_mm, i.rel_tolerance, i.max_step_s, Stepper())) {}

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
    for (int k = 0; k < model->coordinates; ++k) out[k] = s[kRatesAt + k] / rate_scale[k];
  }

  // dx/dt. A failure (the pose out of reach) is kept and the derivative zeroed; advance_to() stops after the
  // step and reports it (the integrator's interface has no error path).
  void derivative(const State& s, State& ds, double time_s) {
    ++counters.evaluations;
    ds.fill(0.0);
    if (!failure) return;
    drives->setpoint(time_s, setpoint);
    rates_of(s, rates);
    const Pose pose = pose_of(s);
    if (Status status = elastic_accelerations(*model, pose, rates, setpoint, workspace, accelerations);
        !status) {
      failure = status;
      return;
    }
    const Eigen::Matrix<double, 6, 1> twist = model->basis * rates;
    for (int i = 0; i < 3; ++i) ds[kPositionAt + i] = twist[i];
    // q̇ = ½ (0, ω) ⊗ q: ẇ = −½ ω·v, v̇ = ½ (w ω + ω × v); linear in q, so the scale L carries through.
    const Eigen::Vector3d omega = twist.tail<3>();
    const double w = s[kQuaternionAt];
    const Eigen::Vector3d v(s[kQuaternionAt + 1], s[kQuaternionAt + 2], s[kQuaternionAt + 3]);
    const Eigen::Vector3d v_rate = 0.5 * (w * omega + omega.cross(v));
    ds[kQuaternionAt] = -0.5 * omega.dot(v);
    for (int i = 0; i < 3; ++i) ds[kQuaternionAt + 1 + i] = v_rate[i];
    for (int k = 0; k < model->coordinates; ++k) ds[kRatesAt + k] = accelerations[k] * rate_scale[k];
  }
};

ElasticSimulator::ElasticSimulator(const ElasticModel& model, const ElasticIntegration& integration)
    : impl_(std::make_unique<Impl>(model, integration)) {}
ElasticSimulator::~ElasticSimulator() = default;
ElasticSimulator::ElasticSimulator(ElasticSimulator&&) noexcept = default;
ElasticSimulator& ElasticSimulator::operator=(ElasticSimulator&&) noexcept = default;

Status ElasticSimulator::start(double time_s, const Pose& pose, const CoordinateVector& rates) {
  Impl& s = *impl_;
  const ElasticModel& model = *s.model;
  if (rates.size() != model.coordinates) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("elastic simulation: {} rates given for {} coordinates", rates.size(),
                                  model.coordinates));
  }
  auto equations = equations_of_motion(*model.mechanism, *model.parameters, pose, model.basis, Twist::Zero());
  if (!equations) return equations.error();
  s.length_mm = model.mechanism->platform_size_mm();
  s.time_scale_s = s.integration.rate_time_scale_s;
  if (!(s.time_scale_s > 0.0)) {
    // τ = 1/ω_max of M x'' + K x = 0 with the elastic elements' stiffness alone.
    const Eigen::GeneralizedSelfAdjointEigenSolver<CoordinateMatrix> modes(
        material_stiffness(model, equations->state), equations->mass, Eigen::EigenvaluesOnly);
    const double omega_max_sq = modes.info() == Eigen::Success ? modes.eigenvalues().maxCoeff() : 0.0;
    s.time_scale_s = omega_max_sq > 0.0 ? 1.0 / std::sqrt(omega_max_sq) : kFallbackTimeScaleS;
  }
  for (int k = 0; k < model.coordinates; ++k) {
    const bool angular = model.basis.col(k).tail<3>().squaredNorm() > 0.0;
    s.rate_scale[k] = s.time_scale_s * (angular ? s.length_mm : 1.0);
  }
  s.origin_mm = equations->state.pose.position_mm;
  s.x.fill(0.0);
  const Eigen::Quaterniond q(equations->state.pose.rotation);
  s.x[kQuaternionAt] = q.w() * s.length_mm;
  s.x[kQuaternionAt + 1] = q.x() * s.length_mm;
  s.x[kQuaternionAt + 2] = q.y() * s.length_mm;
  s.x[kQuaternionAt + 3] = q.z() * s.length_mm;
  for (int k = 0; k < model.coordinates; ++k) s.x[kRatesAt + k] = rates[k] * s.rate_scale[k];
  s.t = time_s;
  double first_step = kFirstStepOfTimeScale * s.time_scale_s;
  if (s.integration.max_step_s > 0.0) first_step = std::min(first_step, s.integration.max_step_s);
  s.stepper.initialize(s.x, time_s, first_step);
  s.last_drives = nullptr;
  s.counters = {};
  return ok_status();
}

Status ElasticSimulator::advance_to(double time_s, const DriveMotion& drives) {
  Impl& s = *impl_;
  if (time_s < s.t) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("elastic simulation: asked for {:.6f} s, before {:.6f} s", time_s, s.t));
  }
  s.drives = &drives;
  if (s.last_drives != &drives) {
    // A new excitation: restart from the state now (no derivative of the old one to reuse, and no step
    // taken under it past now).
    s.stepper.initialize(s.x, s.t, s.stepper.current_time_step());
    s.last_drives = &drives;
  }
  s.failure = ok_status();
  auto system = [&s](const State& x, State& dx, double t) { s.derivative(x, dx, t); };
  long steps = 0;
  try {
    while (s.stepper.current_time() < time_s) {
      if (++steps > s.integration.max_steps_per_advance) {
        return make_error(ErrorCode::not_converged,
                          fmt::format("elastic simulation: more than {} steps from {:.6f} s to {:.6f} s",
                                      s.integration.max_steps_per_advance, s.t, time_s));
      }
      s.stepper.do_step(std::ref(system));
      if (!s.failure) {
        return Error{s.failure.error().code,
                     fmt::format("elastic simulation at {:.6f} s: {}", s.stepper.current_time(),
                                 s.failure.error().message)};
      }
      ++s.counters.accepted_steps;
    }
  } catch (const std::exception& e) {  // Odeint's step-size control gave up: the step size collapsed
    return make_error(ErrorCode::not_converged, fmt::format("elastic simulation near {:.6f} s: {}",
                                                            s.stepper.current_time(), e.what()));
  }
  s.stepper.calc_state(time_s, s.x);  // Dormand–Prince's own interpolant within the last step
  s.t = time_s;
  return ok_status();
}

double ElasticSimulator::time_s() const {
  return impl_->t;
}
Pose ElasticSimulator::pose() const {
  return impl_->pose_of(impl_->x);
}
CoordinateVector ElasticSimulator::rates() const {
  CoordinateVector r;
  impl_->rates_of(impl_->x, r);
  return r;
}
const IntegrationCounters& ElasticSimulator::counters() const {
  return impl_->counters;
}
double ElasticSimulator::rate_time_scale_s() const {
  return impl_->time_scale_s;
}

}  // namespace pkm::dynamics
