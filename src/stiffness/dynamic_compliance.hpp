#pragma once
// The tool's dynamic compliance (Rusanov et al.'s "Tools App": the technological system described by
// its dynamic compliance function, the displacement response to a given force excitation; see
// docs/dynamic_compliance.md): the elastic machine of the elastic dynamics (docs/dynamics_elastic.md),
// linearised at a pose with its drives clamped, gives
//   M δ̈ + C δ̇ + K δ = Bᵀ w(t),         W(iω) = B (K − ω²M + iωC)⁻¹ Bᵀ
// in the basis coordinates δ of the platform (twist d = B δ about the tool point, base frame, B the
// model's twist basis) for a harmonic wrench w = (f N, m N·mm) on the platform. W is in the twist/wrench
// form of the static compliance (strut_compliance.hpp): rows d (mm) and θ (rad), columns f (N) and
// m (N·mm), so W(0) = K⁻¹ mapped is the static compliance (equal to the strut-only one when the springs are
// the same and the gravity preload is left out).
//
// M and K are natural_frequencies.hpp's (K = ∂²Π/∂q², M the mass matrix, det(K − ω²M) = 0).
// Smirnov 2019 gives no damping for the machine (§4.5 reports no damping values), and the
// struts' friction of the elastic model is nonlinear (quadratic, Coulomb), so the damping here is an
// assumption, stated with every result: a modal damping ratio ζ for every mode (C = M Φ diag(2ζω_i) Φᵀ M,
// Φ the M-normalised modes), or Rayleigh damping C = αM + βK (whose ratio is ζ_i = α/(2ω_i) + βω_i/2).
//
// Units: the dynamics' own (mm, kg, s): M in kg and kg·mm², K in kg/s² (N/mm × 10³) per mm or rad, C in
// kg/s; generalised forces in kg·mm/s² (N × 10³). W per N, as the static compliance.
#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "dynamics/elastic_model.hpp"
#include "dynamics/natural_frequencies.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

using ComplexMatrix6 = Eigen::Matrix<std::complex<double>, 6, 6>;
/// A matrix over the basis coordinates (at most six), complex.
using ComplexCoordinateMatrix = Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

/// How the damping is assumed (none is measured: see the header comment).
enum class DampingModel {
  modal,     ///< the same ratio ζ for every mode
  rayleigh,  ///< C = αM + βK
};

struct DampingAssumption {
  DampingModel model = DampingModel::modal;
  /// ζ of every mode (modal). 0.02 is a usual guess for a bolted machine structure; state what you take.
  double modal_ratio = 0.02;
  double rayleigh_mass_per_s = 0.0;   ///< α (rayleigh), 1/s
  double rayleigh_stiffness_s = 0.0;  ///< β (rayleigh), s
};

/// "modal damping ζ = 0.02 for every mode" or "Rayleigh damping C = α·M + β·K, α = … 1/s, β = … s".
std::string describe(const DampingAssumption& damping);
/// Checks the assumption: ζ ≥ 0 and finite, α and β ≥ 0 and finite (bad_input, naming the value).
Status check_damping(const DampingAssumption& damping);
/// The Rayleigh coefficients that give ratio `ratio` at the frequencies f1 and f2 (Hz, f1 ≠ f2):
/// α = 2ζ ω1 ω2 / (ω1 + ω2), β = 2ζ / (ω1 + ω2). Between them the ratio is lower, outside higher.
DampingAssumption rayleigh_for_ratio(double ratio, double f1_Hz, double f2_Hz);

// The lowest level: matrices over coordinates in consistent units (any), for any model.

/// The damping matrix of an assumption for mass M and stiffness K (both symmetric, M positive definite).
/// Fails (singular) where M is not positive definite or K has a non-positive generalised eigenvalue.
Result<dynamics::CoordinateMatrix> damping_matrix(const dynamics::CoordinateMatrix& mass,
                                                  const dynamics::CoordinateMatrix& stiffness,
                                                  const DampingAssumption& damping);
/// C = M Φ diag(2 ζ_i ω_i) Φᵀ M with Φ the M-normalised modes of (K, M), ω_i² their eigenvalues ascending:
/// mode i gets ratio ζ_i exactly (one ratio per mode).
Result<dynamics::CoordinateMatrix> modal_damping_matrix(const dynamics::CoordinateMatrix& mass,
                                                        const dynamics::CoordinateMatrix& stiffness,
                                                        const dynamics::CoordinateVector& ratios);
/// (K − ω²M + iωC)⁻¹ at ω (rad/s): displacement per force in the matrices' own units. Equilibrated by the
/// diagonal of K before the complex LU, so that mm and rad coordinates weigh alike. Fails (singular) where
/// the matrix is singular (ω at an undamped natural frequency).
Result<ComplexCoordinateMatrix> receptance(const dynamics::CoordinateMatrix& mass,
                                           const dynamics::CoordinateMatrix& stiffness,
                                           const dynamics::CoordinateMatrix& damping, double omega_rad_s);

// The machine at a pose.

struct DynamicComplianceOptions {
  /// Linearise about the static equilibrium under gravity with the preload's geometric stiffness (as
  /// `pkm modes`); false: at the commanded pose, K = J_Bᵀ diag(c) J_B only, so that W(0) is exactly the
  /// strut-only compliance of the same springs.
  bool gravity_preload = true;
  DampingAssumption damping;
  dynamics::ModalOptions modal;  ///< with gravity_preload
};

/// The linear model of the tool at a pose: what W(iω) is made of.
struct ToolDynamics {
  Pose pose;  ///< where it is linearised (the equilibrium with gravity_preload, else the commanded pose)
  TwistBasis basis;
  int coordinates = 0;
  dynamics::CoordinateMatrix mass;           ///< M: kg, kg·mm²
  dynamics::CoordinateMatrix stiffness;      ///< K: kg/s² (N/mm × 10³) per mm or rad
  dynamics::CoordinateMatrix damping;        ///< C: kg/s per mm or rad
  dynamics::CoordinateVector frequency_Hz;   ///< undamped natural frequencies, ascending
  dynamics::CoordinateVector damping_ratio;  ///< ζ of each mode under the assumption
  DampingAssumption assumption;
};

/// The model at `pose` from the elastic machine. Fails where natural_modes would (out of reach, singular,
/// unstable), or for a bad damping assumption.
Result<ToolDynamics> tool_dynamics(const dynamics::ElasticModel& model, const Pose& pose,
                                   const DynamicComplianceOptions& options = {});

/// W(i·2πf) at `frequency_Hz` ≥ 0 in the twist/wrench form (mm or rad per N or N·mm); symmetric (not
/// Hermitian). Fails only exactly at an undamped natural frequency of an undamped model.
Result<ComplexMatrix6> dynamic_compliance(const ToolDynamics& dynamics, double frequency_Hz);
/// The same at every frequency of a list.
Result<std::vector<ComplexMatrix6>> dynamic_compliance(const ToolDynamics& dynamics,
                                                       const std::vector<double>& frequencies_Hz);

}  // namespace pkm::stiffness
