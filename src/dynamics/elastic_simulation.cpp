#include "dynamics/elastic_simulation.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace pkm::dynamics {
namespace {

// Where no stiffness tells the time scale (a model whose mass matrix fails at the start, which start() then
// reports anyway): a millisecond.
constexpr double kFallbackTimeScaleS = 1e-3;

}  // namespace

// The elastic machine's equations for the integrator: no auxiliary states.
struct ElasticEquations final : PlatformRightHandSide {
  const ElasticModel* model = nullptr;
  const DriveMotion* drives = nullptr;
  ElasticWorkspace workspace;
  DriveSetpoint setpoint;

  Status evaluate(double time_s, const Pose& pose, const CoordinateVector& rates, const AuxiliaryVector&,
                  CoordinateVector& accelerations, AuxiliaryVector&) override {
    drives->setpoint(time_s, setpoint);
    return elastic_accelerations(*model, pose, rates, setpoint, workspace, accelerations);
  }
};

struct ElasticSimulator::Impl {
  const ElasticModel* model;
  ElasticIntegration integration;
  PlatformIntegrator integrator;
  ElasticEquations equations;
  const DriveMotion* last_drives = nullptr;

  Impl(const ElasticModel& m, const ElasticIntegration& i)
      : model(&m), integration(i), integrator(m, i, "elastic simulation") {
    equations.model = &m;
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
  PlatformScales scales;
  scales.length_mm = model.mechanism->platform_size_mm();
  scales.time_scale_s = s.integration.rate_time_scale_s;
  if (!(scales.time_scale_s > 0.0)) {
    // τ = 1/ω_max of M x'' + K x = 0 with the elastic elements' stiffness alone.
    const Eigen::GeneralizedSelfAdjointEigenSolver<CoordinateMatrix> modes(
        material_stiffness(model, equations->state), equations->mass, Eigen::EigenvaluesOnly);
    const double omega_max_sq = modes.info() == Eigen::Success ? modes.eigenvalues().maxCoeff() : 0.0;
    scales.time_scale_s = omega_max_sq > 0.0 ? 1.0 / std::sqrt(omega_max_sq) : kFallbackTimeScaleS;
  }
  s.integrator.start(time_s, equations->state.pose, rates, AuxiliaryVector(), scales);
  s.last_drives = nullptr;
  return ok_status();
}

Status ElasticSimulator::advance_to(double time_s, const DriveMotion& drives) {
  Impl& s = *impl_;
  if (s.last_drives != &drives) {
    // A new excitation: restart from the state now.
    s.integrator.restart();
    s.last_drives = &drives;
  }
  s.equations.drives = &drives;
  return s.integrator.advance_to(time_s, s.equations);
}

double ElasticSimulator::time_s() const {
  return impl_->integrator.time_s();
}
Pose ElasticSimulator::pose() const {
  return impl_->integrator.pose();
}
CoordinateVector ElasticSimulator::rates() const {
  return impl_->integrator.rates();
}
const IntegrationCounters& ElasticSimulator::counters() const {
  return impl_->integrator.counters();
}
double ElasticSimulator::rate_time_scale_s() const {
  return impl_->integrator.scales().time_scale_s;
}

}  // namespace pkm::dynamics
