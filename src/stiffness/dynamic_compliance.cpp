#include "stiffness/dynamic_compliance.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/units.hpp"

namespace pkm::stiffness {
namespace {

// Below this ratio of the smallest to the largest pivot of the equilibrated dynamic stiffness the matrix is
// singular: ω sits on an undamped natural frequency (or K is singular at ω = 0).
constexpr double kDynamicSingularRatio = 1e-14;

bool dynamic_compliance_finite_non_negative(double value) {
  return std::isfinite(value) && value >= 0.0;
}

// The M-normalised modes of (K, M) and their ω², ascending; fails unless M > 0 and every ω² > 0.
Result<Eigen::GeneralizedSelfAdjointEigenSolver<dynamics::CoordinateMatrix>> dynamic_compliance_modes(
    const dynamics::CoordinateMatrix& mass, const dynamics::CoordinateMatrix& stiffness) {
  Eigen::GeneralizedSelfAdjointEigenSolver<dynamics::CoordinateMatrix> solver(stiffness, mass);
  if (solver.info() != Eigen::Success) {
    return make_error(ErrorCode::singular,
                      "dynamic compliance: the mass matrix is not positive definite (a massless direction)");
  }
  if (!(solver.eigenvalues()[0] > 0.0)) {
    return make_error(ErrorCode::singular,
                      fmt::format("dynamic compliance: not stable (ω² = {:.3g} s⁻² in the softest direction)",
                                  solver.eigenvalues()[0]));
  }
  return solver;
}

}  // namespace

std::string describe(const DampingAssumption& damping) {
  if (damping.model == DampingModel::modal) {
    return fmt::format("modal damping, ratio ζ = {:g} for every mode (assumed)", damping.modal_ratio);
  }
  return fmt::format("Rayleigh damping C = α·M + β·K, α = {:g} 1/s, β = {:g} s (assumed)",
                     damping.rayleigh_mass_per_s, damping.rayleigh_stiffness_s);
}

Status check_damping(const DampingAssumption& damping) {
  if (damping.model == DampingModel::modal && !dynamic_compliance_finite_non_negative(damping.modal_ratio)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("damping ratio must be a finite number ≥ 0, got {}", damping.modal_ratio));
  }
  if (damping.model == DampingModel::rayleigh &&
      (!dynamic_compliance_finite_non_negative(damping.rayleigh_mass_per_s) ||
       !dynamic_compliance_finite_non_negative(damping.rayleigh_stiffness_s))) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("Rayleigh coefficients must be finite numbers ≥ 0, got α = {} 1/s, β = {} s",
                    damping.rayleigh_mass_per_s, damping.rayleigh_stiffness_s));
  }
  return ok_status();
}

DampingAssumption rayleigh_for_ratio(double ratio, double f1_Hz, double f2_Hz) {
  // ζ(ω) = α/(2ω) + βω/2 = ζ at ω1 and ω2.
  const double w1 = 2.0 * kPi * f1_Hz, w2 = 2.0 * kPi * f2_Hz;
  DampingAssumption d;
  d.model = DampingModel::rayleigh;
  d.rayleigh_mass_per_s = 2.0 * ratio * w1 * w2 / (w1 + w2);
  d.rayleigh_stiffness_s = 2.0 * ratio / (w1 + w2);
  return d;
}

Result<dynamics::CoordinateMatrix> modal_damping_matrix(const dynamics::CoordinateMatrix& mass,
                                                        const dynamics::CoordinateMatrix& stiffness,
                                                        const dynamics::CoordinateVector& ratios) {
  auto modes = dynamic_compliance_modes(mass, stiffness);
  if (!modes) return modes.error();
  if (ratios.size() != mass.rows()) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{} damping ratios for {} modes", ratios.size(), mass.rows()));
  }
  // Φᵀ M Φ = I and Φᵀ K Φ = diag(ω²), so Φᵀ C Φ = diag(2ζω) for C = M Φ diag(2ζω) Φᵀ M.
  const dynamics::CoordinateMatrix& phi = modes->eigenvectors();
  const dynamics::CoordinateVector modal = 2.0 * ratios.cwiseProduct(modes->eigenvalues().cwiseSqrt());
  const dynamics::CoordinateMatrix mphi = mass * phi;
  dynamics::CoordinateMatrix c = mphi * modal.asDiagonal() * mphi.transpose();
  return dynamics::CoordinateMatrix(0.5 * (c + c.transpose()));
}

Result<dynamics::CoordinateMatrix> damping_matrix(const dynamics::CoordinateMatrix& mass,
                                                  const dynamics::CoordinateMatrix& stiffness,
                                                  const DampingAssumption& damping) {
  if (Status s = check_damping(damping); !s) return s.error();
  if (damping.model == DampingModel::rayleigh) {
    return dynamics::CoordinateMatrix(damping.rayleigh_mass_per_s * mass +
                                      damping.rayleigh_stiffness_s * stiffness);
  }
  return modal_damping_matrix(mass, stiffness,
                              dynamics::CoordinateVector::Constant(mass.rows(), damping.modal_ratio));
}

Result<ComplexCoordinateMatrix> receptance(const dynamics::CoordinateMatrix& mass,
                                           const dynamics::CoordinateMatrix& stiffness,
                                           const dynamics::CoordinateMatrix& damping, double omega_rad_s) {
  const std::complex<double> i_omega(0.0, omega_rad_s);
  const ComplexCoordinateMatrix dynamic_stiffness =
      (stiffness - omega_rad_s * omega_rad_s * mass).cast<std::complex<double>>() +
      i_omega * damping.cast<std::complex<double>>();
  // Equilibrate by K's diagonal (the static scale of each coordinate), so that mm and rad rows weigh alike.
  const dynamics::CoordinateVector scale = stiffness.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
  if (!scale.allFinite()) {
    return make_error(ErrorCode::singular, "dynamic compliance: a coordinate without stiffness");
  }
  const ComplexCoordinateMatrix scaled = scale.cast<std::complex<double>>().asDiagonal() * dynamic_stiffness *
                                         scale.cast<std::complex<double>>().asDiagonal();
  const Eigen::FullPivLU<ComplexCoordinateMatrix> lu(scaled);
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  // The equilibrated K has a unit diagonal: pivots are measured against 1 as well as against each other, so
  // that a single coordinate at its resonance is caught too.
  if (!(pivots.minCoeff() > kDynamicSingularRatio * std::max(1.0, pivots.maxCoeff()))) {
    return make_error(
        ErrorCode::singular,
        fmt::format("dynamic compliance: unbounded at {:g} rad/s (an undamped natural frequency)",
                    omega_rad_s));
  }
  const ComplexCoordinateMatrix inverse = lu.inverse();
  return ComplexCoordinateMatrix(scale.cast<std::complex<double>>().asDiagonal() * inverse *
                                 scale.cast<std::complex<double>>().asDiagonal());
}

Result<ToolDynamics> tool_dynamics(const dynamics::ElasticModel& model, const Pose& pose,
                                   const DynamicComplianceOptions& options) {
  if (Status s = check_damping(options.damping); !s) return s.error();
  ToolDynamics out;
  out.basis = model.basis;
  out.coordinates = model.coordinates;
  out.assumption = options.damping;
  if (options.gravity_preload) {
    // As `pkm modes`: about the sagged equilibrium, the preload's geometric stiffness included.
    auto modes = dynamics::natural_modes(model, pose, options.modal);
    if (!modes) return modes.error();
    out.pose = modes->equilibrium.pose;
    out.mass = modes->mass;
    out.stiffness = modes->stiffness;
  } else {
    // The springs alone at the commanded pose: K = J_Bᵀ diag(c) J_B is the strut-only stiffness in the
    // basis (strut_compliance.hpp's K_T with T = B), so W(0) is that compliance.
    const Mechanism& mechanism = *model.mechanism;
    auto completed = mechanism.complete_pose(pose);
    if (!completed) return completed.error();
    ActuatorVector drives(mechanism.actuator_count());
    if (!mechanism.actuator_values(*completed, drives.data())) {
      return make_error(ErrorCode::unreachable, "dynamic compliance: the pose is out of reach");
    }
    auto equations = dynamics::equations_of_motion(mechanism, *model.parameters, *completed, model.basis,
                                                   dynamics::Twist::Zero());
    if (!equations) return equations.error();
    out.pose = *completed;
    out.mass = equations->mass;
    out.stiffness = dynamics::material_stiffness(model, equations->state);
  }
  auto modes = dynamic_compliance_modes(out.mass, out.stiffness);
  if (!modes) return modes.error();
  const dynamics::CoordinateVector omega = modes->eigenvalues().cwiseSqrt();
  out.frequency_Hz = omega / (2.0 * kPi);
  if (options.damping.model == DampingModel::modal) {
    out.damping_ratio = dynamics::CoordinateVector::Constant(out.coordinates, options.damping.modal_ratio);
  } else {
    out.damping_ratio = (options.damping.rayleigh_mass_per_s * 0.5 * omega.cwiseInverse() +
                         options.damping.rayleigh_stiffness_s * 0.5 * omega)
                            .eval();
  }
  auto c = damping_matrix(out.mass, out.stiffness, options.damping);
  if (!c) return c.error();
  out.damping = *c;
  return out;
}

Result<ComplexMatrix6> dynamic_compliance(const ToolDynamics& dynamics, double frequency_Hz) {
  if (!(std::isfinite(frequency_Hz) && frequency_Hz >= 0.0)) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("dynamic compliance: frequency must be a finite number ≥ 0 Hz, got {}", frequency_Hz));
  }
  auto h = receptance(dynamics.mass, dynamics.stiffness, dynamics.damping, 2.0 * kPi * frequency_Hz);
  if (!h) return h.error();
  // δ = H Q with Q = Bᵀ w · 10³ (N → kg·mm/s²), d = B δ.
  const auto basis = dynamics.basis.cast<std::complex<double>>();
  // Not symmetrised: W = Wᵀ follows from symmetric M, K and C, and a test holds it.
  return ComplexMatrix6(dynamics::kKgMmS2PerN * (basis * *h * basis.transpose()));
}

Result<std::vector<ComplexMatrix6>> dynamic_compliance(const ToolDynamics& dynamics,
                                                       const std::vector<double>& frequencies_Hz) {
  std::vector<ComplexMatrix6> out;
  out.reserve(frequencies_Hz.size());
  for (double f : frequencies_Hz) {
    auto w = dynamic_compliance(dynamics, f);
    if (!w) return w.error();
    out.push_back(*w);
  }
  return out;
}

}  // namespace pkm::stiffness
