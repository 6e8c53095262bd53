#pragma once
// The elastic-dissipative machine (Smirnov 2019, §4.2 for the planar biped, §4.5 model S2 for the hexapod),
// for every mechanism whose platform moves freely in a twist basis (platform_twist_basis): the drives hold
// the actuator coordinates q_j(t) (kinematic excitation, §4.2 / §4.5), and an elastic element in series with
// each strut carries the axial force
//   F_j = c_j (a_j − q_j) + D_j(ȧ_j − q̇_j),    a_j = the actuator value of the platform's actual pose,
// with a_j = |B_j − A_j| for struts whose actuators are their lengths (Smirnov's δl = L* − q, eqs.
// (137)-(139) and §4.2) and D the element's friction: viscous β·ẋ, quadratic β·ẋ·|ẋ| (Smirnov's "true
// friction", §4.2, §4.5, signed to dissipate, corrected), Coulomb β·tanh(ẋ/v_ε) (sign() smoothed
// over v_ε). F > 0 stretches the element and pulls the platform joint towards the base: with the rigid terms
// of equations_of_motion.hpp and J_B the drive Jacobian in the basis,
//   M(pose) c̈ = applied(pose) − bias(pose, ċ) − J_Bᵀ F · 10³          (kg·mm/s², F in N)
// which is Lagrange's (109) with Π = ½ Σ c_j (a_j − q_j)², ∂Π/∂c = J_Bᵀ c (a − q), and the friction's
// generalised force −J_Bᵀ D (signs from the Lagrangian, corrected from the printed (141)).
//
// The platform's coordinates are its pose (tool point and rotation matrix, integrated as a rotation,
// elastic_simulation.hpp) and the rates ċ of the basis coordinates (twist t = B ċ), so no small-angle
// assumption enters (Smirnov's 10° limit of (138) is lifted). The moving bodies are those of
// body_motion.hpp: each strut's parts move with its joints A_j and B_j (docs/dynamics_elastic.md says what
// this lumps relative to S2's twelve coordinates). Units: mm, kg, s; forces leave in N, energies in J.
#include <Eigen/Core>
#include <array>

#include "core/result.hpp"
#include "dynamics/body_motion.hpp"
#include "dynamics/equations_of_motion.hpp"
#include "dynamics/free_platform.hpp"
#include "dynamics/rigid_terms.hpp"
#include "machine/machine.hpp"

namespace pkm::dynamics {

/// Where the drives hold the actuator coordinates at one instant, and how fast they move them.
struct DriveSetpoint {
  ActuatorVector position_mm;
  ActuatorVector rate_mm_s;
  /// The process load on the platform at that instant (the cut: N, N·mm about the tool point), zero
  /// unless given.
  statics::Wrench load;
};

/// Settings of the elastic model that are not machine data.
struct ElasticModelOptions {
  /// Coulomb friction β·sign(ẋ) is smoothed to β·tanh(ẋ / v_ε): a discontinuous force would stall an
  /// adaptive integrator at every reversal. Below v_ε the element acts as a viscous one of β / v_ε.
  double coulomb_smoothing_mm_s = 0.01;
  /// Lost motion in each drive's transmission (backlash), mm: the element carries no force while its
  /// elongation is within half the gap either way, and is stretched by what exceeds it (0: none).
  std::array<double, kMaxActuators> lost_motion_mm{};
  /// Viscous damping in series with each drive (its transmission's), N·s/mm, added to the element's own
  /// friction D (0: none).
  std::array<double, kMaxActuators> series_damping_N_s_per_mm{};
};

/// The immutable model: the free platform (free_platform.hpp) with the elastic model's settings.
struct ElasticModel : FreePlatformModel {
  ElasticModelOptions options;
};

/// Builds the model, or says why the machine cannot have one: no dynamics section, a strut without
/// stiffness_N_mm, angular actuators, or a platform without a free twist basis (tripod, tricept). Errors name
/// the machine file, the line of its `dynamics:` section and the key. The machine must outlive the model; its
/// struts' parameters are read at every evaluation, the platform and payload only here.
Result<ElasticModel> make_elastic_model(const Machine& machine, const ElasticModelOptions& options = {});
/// The same from parts (the checks without a file to name; for tests and library callers).
Result<ElasticModel> make_elastic_model(const Mechanism& mechanism, const DynamicsParameters& parameters,
                                        const ElasticModelOptions& options = {});

/// Preallocated per-evaluation storage (the right-hand side runs several times per integration step).
struct ElasticWorkspace {
  MechanismState state;
  RigidTerms rigid;
  /// The six coordinates' terms (the platform's own twist); the Cholesky solve factors its mass in place.
  TwistRigidTerms twist_rigid;
};

/// The elastic elements' state at a pose moving with rates ċ under a drive setpoint.
struct StrutForces {
  ActuatorVector elongation_mm;         ///< a_j − q_j, less the lost motion taken up
  ActuatorVector elongation_rate_mm_s;  ///< ȧ_j − q̇_j = (J_B ċ)_j − q̇_j
  ActuatorVector force_N;               ///< c (a − q) + D(ȧ − q̇), positive in tension
};

/// The elastic element's friction force for an elongation rate, N (positive opposes stretching).
double damping_force_N(const StrutDynamics& strut, double elongation_rate_mm_s,
                       const ElasticModelOptions& options);

/// The coordinate accelerations c̈ at `pose` (complete) moving with `rates` under `drives`, plus the strut
/// forces when `forces` is given. Fails (ErrorCode::unreachable / singular) where the pose leaves the
/// mechanism's reach or the mass matrix is not positive definite. Never allocates.
Status elastic_accelerations(const ElasticModel& model, const Pose& pose, const CoordinateVector& rates,
                             const DriveSetpoint& drives, ElasticWorkspace& workspace,
                             CoordinateVector& accelerations, StrutForces* forces = nullptr);

/// The energies of the elastic machine: kinetic T, elastic Π = ½ Σ c (a − q)², gravity V = −Σ m g·c.
struct ElasticEnergy {
  double kinetic_J = 0.0;
  double elastic_J = 0.0;
  double gravity_J = 0.0;
  double total_J() const { return kinetic_J + elastic_J + gravity_J; }
};
Result<ElasticEnergy> elastic_energy(const ElasticModel& model, const Pose& pose,
                                     const CoordinateVector& rates, const ActuatorVector& drive_position_mm);

/// The stiffness of the elastic elements in the basis coordinates at a state: J_Bᵀ diag(c) J_B, with c in
/// kg/s² (N/mm × 10³), so that with M in kg and kg·mm² the eigenvalues are ω² in 1/s².
CoordinateMatrix material_stiffness(const ElasticModel& model, const MechanismState& state);

}  // namespace pkm::dynamics
